# Verney shell split at r = 9 cm by contact, non-matching meshes
# (docs/problems.md, D6): the inner surface stops within 0.1 cm of the
# single-shell run.
foreach(m dlm dam)
  impact3d_check(contact/verney_split_${m} "regression;contact;solids" shell_stop
    --workdir ${WORK}/verney_split_${m}
    --deck ${PROBLEMS}/verney_contact/verney_contact_${m}.nml
    --reference ${PROBLEMS}/verney/verney.nml --np 2 --origin 8.0 --tol 0.1)
endforeach()
