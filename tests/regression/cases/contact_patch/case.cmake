# Patch test: non-matching meshes (4 x 4 against 5 x 5 zones); the stress
# transmitted by a planar wave is uniform across the section (variation and
# mean within 1%) in the layers behind the interface.
foreach(m dlm dam)
  impact3d_check(contact/patch_${m} "regression;contact" patch --workdir ${WORK}/patch_${m}
    --deck ${CMAKE_CURRENT_LIST_DIR}/patch_${m}.nml --range 1.0 1.35 --target=-1e-3 --tol 0.01)
  # Every dump bitwise identical on 1, 2, 3 and 4 ranks.
  impact3d_check(parallel/bitwise_patch_${m} "regression;parallel;contact" bitwise
    --workdir ${WORK}/bitwise_patch_${m} --deck ${CMAKE_CURRENT_LIST_DIR}/patch_${m}.nml
    --ranks 1 2 3 4)
endforeach()
