# A cube driven edge-first (45 degrees) or vertex-first (body diagonal along
# the plate normal) into a plate with zones half the cube's, both methods
# (docs/contact.md, 9.3). Criteria, none taken from a measurement:
# * the energy balance, with the contact work booked, closes to 1e-12
#   (round-off of the compatible scheme);
# * at every audit no node of either surface is deeper than its tolerance and
#   no penetrating node is unheld;
# * the audit's deepest cube node (surface a) within 5% of the plate's
#   segment, 0.05 x 0.0625 cm: a cube node's default tolerance is 5% of the
#   smaller of its own and the opposite segment, and the flat plate has no
#   faceting sagitta;
# * the contact work never positive beyond round-off (1e-10 of the initial
#   energy): a contact that only pushes and stops approaches dissipates.
foreach(c edge_dam vertex_dam edge_dlm vertex_dlm)
  impact3d_check(contact/corner_${c} "regression;contact" impact
    --workdir ${WORK}/corner_${c} --deck ${CMAKE_CURRENT_LIST_DIR}/${c}.nml --np 2
    --pair hit --tol 1e-12 --audit --max-audit-a 3.125e-3 --max-work 1e-10)
endforeach()
# DLM's node shares over its gated facet pairs are summed across the RCB
# parts by the owners: every dump bitwise identical on 1, 2, 3 and 4 ranks;
# history.txt too, but for the interface's force, pen_rms and dmom columns
# (sums over the contact parts, docs/user-guide.md "history.txt").
impact3d_check(parallel/bitwise_corner_edge_dlm "regression;parallel;contact" bitwise
  --workdir ${WORK}/bitwise_corner_edge_dlm --deck ${CMAKE_CURRENT_LIST_DIR}/edge_dlm.nml
  --ranks 1 2 3 4 --history --history-except _force _pen_rms _dmom_x _dmom_y _dmom_z)
