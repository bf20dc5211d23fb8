# Bitwise identity of every dump on 1, 2, 3, 4 and 8 ranks (shared decks), and
# of history.txt byte for byte (its global sums are exact, core_exact_sum).
foreach(p sod_small sedov_small)
  impact3d_check(parallel/bitwise_${p} "regression;parallel" bitwise
    --workdir ${WORK}/bitwise_${p} --deck ${DECKS}/${p}.nml --ranks 1 2 3 4 8 --history)
endforeach()
