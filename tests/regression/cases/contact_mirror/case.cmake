# Mirror test: a block hitting its mirror image through contact equals the
# block on the rigid unilateral wall, node positions within 1e-8 of its size.
# Self-contact: the same with one contact surface made of both facing sides
# (DAM also with the reverse pass, symmetric = .true.).
foreach(m dlm dam self_dlm self_dam self_dam_sym)
  impact3d_check(contact/mirror_${m} "regression;contact" mirror --workdir ${WORK}/mirror_${m}
    --deck ${CMAKE_CURRENT_LIST_DIR}/mirror_${m}.nml
    --reference ${CMAKE_CURRENT_LIST_DIR}/mirror_wall.nml --axis z --tol 1e-8)
endforeach()
# Contact on RCB parts: every dump bitwise identical on 1, 2, 3 and 4 ranks
# (each rank runs its own pairs; the owners sum the contributions in global
# key order).
foreach(m dlm dam self_dlm self_dam self_dam_sym)
  impact3d_check(parallel/bitwise_mirror_${m} "regression;parallel;contact" bitwise
    --workdir ${WORK}/bitwise_mirror_${m} --deck ${CMAKE_CURRENT_LIST_DIR}/mirror_${m}.nml
    --ranks 1 2 3 4)
endforeach()
