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
