# Per-material energy columns (issue 20 item 4): the material sums equal the
# totals to round-off; plastic work >= 0, non-decreasing, bounded by the
# internal-energy rise, 0 when elastic.
impact3d_regress(energy/material_breakdown "regression;solids;parallel"
  ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check.py ${EXE}
  ${WORK}/energy_breakdown --mpiexec ${MPIEXEC_EXECUTABLE} --np 2)
