# Material parameters in the deck (issue 17 item 1): each deck's material given
# by keys only, no library, with the library set's values, writes every dump
# bitwise identical (h5diff, /run excluded) to the library deck's run (the
# library decks are in their own case folders).
foreach(d elastic_wave/elastic_wave wilkins_piston/wilkins_piston bar_wall/bar_wall
    bar_wall/bar_wall_plastic bar_wall/bar_wall_sg bar_wall/bar_wall_jc)
  get_filename_component(n ${d} NAME)
  impact3d_check(solids/keys_${n} "regression;solids" same --workdir ${WORK}/keys_${n}
    --deck ${CMAKE_CURRENT_LIST_DIR}/${n}_keys.nml --reference ${CASES}/${d}.nml --np 1)
endforeach()
impact3d_check(solids/keys_taylor_small "regression;solids;parallel" same
  --workdir ${WORK}/keys_taylor_small --deck ${CMAKE_CURRENT_LIST_DIR}/taylor_small_keys.nml
  --reference ${DECKS}/taylor_small.nml --np 2)
