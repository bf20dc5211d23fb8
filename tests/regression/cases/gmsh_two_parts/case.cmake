# Meshes from other tools (issue 20 item 5). A Gmsh projectile (physical
# volume) and a generated plate in one deck, the mesh path taken from the
# deck's directory: it runs; the imported coordinates and volume equal the
# file's; energy and DLM momentum to 1e-12; a missing file names the full path
# tried.
impact3d_regress(mesh/gmsh_two_parts "regression;parallel;contact"
  ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check.py ${EXE}
  ${WORK}/gmsh_two_parts --mpiexec ${MPIEXEC_EXECUTABLE} --np 2)
