# Bitwise identity of every dump on 1, 2, 3, 4 and 8 ranks (shared decks), and
# of history.txt byte for byte (its global sums are exact, core_exact_sum).
foreach(p sod_small sedov_small)
  impact3d_check(parallel/bitwise_${p} "regression;parallel" bitwise
    --workdir ${WORK}/bitwise_${p} --deck ${DECKS}/${p}.nml --ranks 1 2 3 4 8 --history)
endforeach()
# Curved parts generated per rank (a whole ball and a quarter shell): the
# same bitwise identity.
impact3d_check(parallel/bitwise_sphere_sectors "regression;parallel" bitwise
  --workdir ${WORK}/bitwise_sphere_sectors --deck ${CMAKE_CURRENT_LIST_DIR}/sphere_sectors.nml
  --ranks 1 2 3 4 8 --history)
