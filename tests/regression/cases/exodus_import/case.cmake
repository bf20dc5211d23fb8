# An Exodus II mesh made by gmsh + meshio + netCDF4 (make_mesh.py):
# coordinates, connectivity, volumes, face-set areas and centres equal the
# file's; its two element blocks impact through DAM and DLM contact (energy to
# 1e-12, no penetration beyond tolerance, momentum); clear input errors.
foreach(m dam dlm)
  impact3d_regress(mesh/exodus_import_${m} "regression;parallel;contact"
    ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check.py ${EXE}
    ${WORK}/exodus_import_${m} --method ${m} --mpiexec ${MPIEXEC_EXECUTABLE} --np 2)
endforeach()
# The imported mesh with DAM contact: every dump bitwise identical on 1-4 ranks.
file(READ ${CMAKE_CURRENT_LIST_DIR}/impact.nml _deck)
string(REPLACE "@METHOD@" "dam" _deck "${_deck}")
string(REPLACE "'two_blocks.exo'"
  "'${CMAKE_CURRENT_LIST_DIR}/two_blocks.exo'" _deck "${_deck}")
file(WRITE ${WORK}/decks/exodus_import_dam.nml "${_deck}")
impact3d_check(parallel/bitwise_exodus_import "regression;parallel;contact" bitwise
  --workdir ${WORK}/bitwise_exodus --deck ${WORK}/decks/exodus_import_dam.nml --ranks 1 2 3 4)
