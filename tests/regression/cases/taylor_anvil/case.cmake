# --- long: Taylor anvil on a rigid wall, both cases, two meshes (final L and
# foot D are reported in docs/verification-solids.md; asserted here: the run
# reaches t_end (149 us after impact for case 1, 200 us for case 2) and the
# energy balance, plastic work and wall reaction included, closes to round-off).
foreach(case taylor_case1_coarse taylor_case2_coarse taylor_case1_fine taylor_case2_fine)
  impact3d_check(long/${case} "long;solids" energy --workdir ${WORK}/${case}
    --deck ${PROBLEMS}/taylor/${case}.nml --np 2 --tol 1e-12)
endforeach()
