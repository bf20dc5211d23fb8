# A cube driven edge-first (45 degrees) or vertex-first (body diagonal along
# the plate normal) into a plate with zones half the cube's: the contact must
# hold a convex edge or corner (no node beyond its tolerance, none unheld, no
# energy injected), both methods (docs/contact.md, 9.3).
foreach(c edge_dam vertex_dam edge_dlm vertex_dlm)
  impact3d_regress(contact/corner_${c} "regression;contact"
    ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check.py ${EXE} ${WORK}/corner_${c}
    --deck ${CMAKE_CURRENT_LIST_DIR}/${c}.nml --mpiexec ${MPIEXEC_EXECUTABLE} --np 2)
endforeach()
# DLM's node shares over its gated facet pairs are summed across the RCB
# parts by the owners: every dump bitwise identical on 1, 2, 3 and 4 ranks.
impact3d_check(parallel/bitwise_corner_edge_dlm "regression;parallel;contact" bitwise
  --workdir ${WORK}/bitwise_corner_edge_dlm --deck ${CMAKE_CURRENT_LIST_DIR}/edge_dlm.nml
  --ranks 1 2 3 4)
