# Crossed tubes (docs/problems.md, D4/D5, long): penetration below 5% of the wall
# (0.01 cm), energy balance to round-off, momentum exact along z (the impact
# direction) for both methods: the total momentum summed over the nodes (not
# the contact's books); the quarter model's symmetry planes x = 0 and y = 0
# take the reactions of the contact forces' x and y components, as the
# mirrored quarters would.
foreach(v same stiff)
  impact3d_check(long/tubes_${v}_dlm "long;contact;solids" impact --workdir ${WORK}/tubes_${v}_dlm
    --deck ${PROBLEMS}/tubes/tubes_${v}_dlm.nml --pair cross --tol 1e-12 --max-pen 0.01
    --momentum-tol 1e-12 --momentum-axes z --np 2)
  impact3d_check(long/tubes_${v}_dam "long;contact;solids" impact --workdir ${WORK}/tubes_${v}_dam
    --deck ${PROBLEMS}/tubes/tubes_${v}_dam.nml --pair cross --tol 1e-12 --max-pen 0.01
    --momentum-tol 1e-12 --momentum-axes z --np 2)
endforeach()
