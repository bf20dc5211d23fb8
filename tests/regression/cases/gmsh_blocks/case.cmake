# An imported Gmsh mesh runs (blocks from physical volumes), energy to round-off.
file(READ ${CMAKE_CURRENT_LIST_DIR}/gmsh_blocks.nml _deck)
string(REPLACE "@DATA@" "${CMAKE_SOURCE_DIR}/tests/unit/data" _deck "${_deck}")
file(WRITE ${WORK}/decks/gmsh_blocks.nml "${_deck}")
impact3d_check(energy/gmsh_mesh "regression;parallel" energy --workdir ${WORK}/energy_gmsh
  --deck ${WORK}/decks/gmsh_blocks.nml --np 2 --tol 1e-12)
# The same mesh on 1-4 ranks: every dump bitwise identical.
string(REPLACE "status_every = 100000 /" "status_every = 100000, dump_cycles = 10 /" _deck "${_deck}")
file(WRITE ${WORK}/decks/gmsh_blocks_dumps.nml "${_deck}")
impact3d_check(parallel/bitwise_gmsh_mesh "regression;parallel" bitwise
  --workdir ${WORK}/bitwise_gmsh --deck ${WORK}/decks/gmsh_blocks_dumps.nml --ranks 1 2 3 4)
