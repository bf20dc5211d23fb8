# Folding tube (issue 16 item 6, long): an Al tube crushed 2.4 cm between
# rigid platens folds, and its self-contact must hold the folds
# (problems/tube_fold). Criteria, none taken from a measurement:
# * the energy balance, with the contact work booked, closes to 1e-12;
# * at every audit no node of either surface of the outer (fold) and inner
#   (foldin) self-contact, or of the platen contacts (press, rest), deeper
#   than its default tolerance, and none unheld (the issue's criterion);
# * the self-contact work never positive beyond round-off (1e-10 of the
#   initial energy): contact that only pushes and stops approaches
#   dissipates (DAM did +1.7e-5, 1.2% of the platen's input, at the closed
#   fold's crease before its momentum correction applied in self-contact).
impact3d_check(long/tube_fold_dam "long;contact;solids" impact --workdir ${WORK}/tube_fold_dam
  --deck ${PROBLEMS}/tube_fold/fold_dam.nml --pair fold foldin --tol 1e-12
  --audit --max-work 1e-10 --np 2)
impact3d_check(long/tube_fold_dlm "long;contact;solids" impact --workdir ${WORK}/tube_fold_dlm
  --deck ${PROBLEMS}/tube_fold/fold_dlm.nml --pair fold foldin --tol 1e-12
  --audit --max-work 1e-10 --np 2)

# Rigid slaves with friction (default suite): the same tube over its first
# 3 us, with the platen contacts in DAM's default two passes, so that the
# reverse pass makes the rigid platens' nodes slaves of the tube. A rigid
# slave keeps its prescribed velocity, so it must give the tube no friction
# reaction: before the fix its reaction, the rigid node's scaled mass
# (1e12 times its own) times a velocity bounded only by round-off, crushed
# a zone of the tube's top ring in cycle 3 (negative volume, exit 2).
# Criteria: the run ends at t_end, the energy balance with the contact
# work booked closes to 1e-12, and no node of either side of any of the
# four contacts is beyond its default tolerance or unheld at any audit.
impact3d_check(contact/rigid_slave_friction_dam "contact;solids" impact
  --workdir ${WORK}/rigid_slave_friction_dam
  --deck ${CMAKE_CURRENT_LIST_DIR}/rigid_slave_friction_dam.nml
  --pair press rest fold foldin --tol 1e-12 --audit --np 2)
