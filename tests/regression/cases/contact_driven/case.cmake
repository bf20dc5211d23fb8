# A punch whose every node is on a velocity boundary (prescribed motion)
# pressed into a plate through contact (docs/contact.md, 4.1): the contact
# treats prescribed nodes as rigid, so the plate under the punch moves with
# it. Before, the contact slowed the punch's nodes, the boundary restored
# them, and with DAM (the punch the slave) the punch sank 8.5e-3 cm into the
# plate in 4 us. Criteria, none taken from a measurement:
# * the energy balance, with the contact work booked, closes to 1e-12
#   (round-off of the compatible scheme);
# * at every audit no node of either surface deeper than its tolerance and
#   none unheld;
# * the deepest node of either surface by the audit within 5% of the
#   plate's segment (0.05 x 0.0625 cm = 3.125e-3 cm): the default tolerance's
#   size term; both surfaces are flat at t = 0, so the tolerance has no
#   faceting sagitta to add, and a dent's curvature must not widen it here.
# (DAM with the punch the master is not a test: plate slave nodes at the
# punch's edges are reported up to 5e-2 cm inside the punch with and without
# the rigid treatment; see docs/contact.md, 4.1.)
foreach(c punch_dam punch_dlm)
  impact3d_check(contact/driven_${c} "regression;contact" impact
    --workdir ${WORK}/driven_${c} --deck ${CMAKE_CURRENT_LIST_DIR}/${c}.nml --np 2
    --pair hit --tol 1e-12 --audit --max-audit-a 3.125e-3 --max-audit-b 3.125e-3)
endforeach()
# The rigid flag is summed over the owners like the masses: every dump
# bitwise identical on 1, 2, 3 and 4 ranks.
impact3d_check(parallel/bitwise_driven_punch_dam "regression;parallel;contact" bitwise
  --workdir ${WORK}/bitwise_driven_punch_dam --deck ${CMAKE_CURRENT_LIST_DIR}/punch_dam.nml
  --ranks 1 2 3 4 --history --history-except _force _pen_rms _dmom_x _dmom_y _dmom_z)
