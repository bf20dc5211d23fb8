# Two-material Sod on non-matching meshes joined by contact (docs/problems.md, D1):
# L1(rho) within 10% of the conforming run; the interface never opens.
foreach(m dlm dam)
  impact3d_check(contact/sod_nonmatching_${m} "regression;contact" relative
    --workdir ${WORK}/sod_contact_${m} --deck ${CMAKE_CURRENT_LIST_DIR}/sod_contact_${m}.nml
    --reference ${CMAKE_CURRENT_LIST_DIR}/sod_conforming.nml --problem sod --key L1_rho
    --tol 0.1 --pair mid)
  # The same with two materials (gamma 1.4 | 5/3), as the seed paper ran its
  # Test 1: L1(rho) against the exact two-gamma solution within 10% of the
  # conforming two-material run; the interface never opens.
  impact3d_check(contact/riemann2_nonmatching_${m} "regression;contact" relative
    --workdir ${WORK}/riemann2_contact_${m}
    --deck ${CMAKE_CURRENT_LIST_DIR}/riemann2_contact_${m}.nml
    --reference ${CMAKE_CURRENT_LIST_DIR}/riemann2_conforming.nml --problem riemann2
    --key L1_rho --tol 0.1 --pair mid)
endforeach()
# Every dump bitwise identical on 1, 2, 3 and 4 ranks.
foreach(m dam dlm)
  impact3d_check(parallel/bitwise_sod_contact_${m} "regression;parallel;contact" bitwise
    --workdir ${WORK}/bitwise_sod_contact_${m}
    --deck ${CMAKE_CURRENT_LIST_DIR}/sod_contact_${m}.nml --ranks 1 2 3 4)
endforeach()
