# Taylor anvil with contact (docs/problems.md, D7, long): against an anvil 100x
# stiffer than steel the final length and foot diameter are within 2% of the
# rigid-wall run; on the steel anvil DAM and DLM agree within 2%.
foreach(c 1 2)
  foreach(m dlm dam)
    impact3d_check(long/taylor_case${c}_stiff_${m} "long;contact;solids" shape
      --workdir ${WORK}/taylor_stiff_${c}_${m}
      --deck ${PROBLEMS}/taylor_contact/taylor_case${c}_stiff_${m}_coarse.nml
      --reference ${PROBLEMS}/taylor/taylor_case${c}_coarse.nml --tol 0.02 --np 2)
  endforeach()
  impact3d_check(long/taylor_case${c}_steel_dam_vs_dlm "long;contact;solids" shape
    --workdir ${WORK}/taylor_steel_${c}
    --deck ${PROBLEMS}/taylor_contact/taylor_case${c}_steel_dam_coarse.nml
    --reference ${PROBLEMS}/taylor_contact/taylor_case${c}_steel_dlm_coarse.nml --tol 0.02 --np 2)
endforeach()
