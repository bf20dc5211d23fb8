# The layering of src/ (docs/design.md): every use statement against the
# order core <- parallel <- mesh <- eos/material <- hydro <- contact <- solver
# <- io <- app; no MPI outside src/parallel.
impact3d_regress(docs/layers "regression"
  ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check.py ${CMAKE_SOURCE_DIR}/src)
