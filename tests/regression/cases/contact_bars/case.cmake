# --- Contact (docs/problems.md, section C) --------------------------------------
# Equal bars: contact lasts 2L/c, interface stress rho c v0, interface at rest,
# each bar leaves at its impact speed reversed (all within 2%); momentum to
# round-off. Dissimilar bars: impedance-matched stress and interface velocity.
# The two-surface decks are shared (tests/regression/decks: bars_energy and
# energy_breakdown run them too).
set(BARS_EQUAL --tol 0.02 --area 1e-4 --duration 3.12073 --stress 1.73229e-3 --v-left=1e-3
  --v-right=-1e-3 --v-interface=0 --final-left=-1e-3 --final-right=1e-3 --momentum-tol 1e-12)
foreach(m dlm dam)
  impact3d_check(contact/bars_equal_${m} "regression;contact" bars
    --workdir ${WORK}/bars_equal_${m} --deck ${DECKS}/bars_equal_${m}.nml ${BARS_EQUAL})
  impact3d_check(contact/bars_dissimilar_${m} "regression;contact" bars
    --workdir ${WORK}/bars_dissimilar_${m} --deck ${DECKS}/bars_dissimilar_${m}.nml --tol 0.02
    --area 1e-4 --duration 3.12073 --stress 1.25828e-3 --v-left=1e-3 --v-right=0
    --v-interface=2.7364e-4 --final-left=-4.5273e-4 --final-right=4.9705e-4
    --momentum-tol 1e-12)
endforeach()
# Self-contact: the equal bars with one contact surface made of both facing
# sides (surface_a = 'x, y', no surface_b); the same exact criteria as with
# two surfaces.
foreach(m dlm dam)
  impact3d_check(contact/bars_self_${m} "regression;contact" bars
    --workdir ${WORK}/bars_self_${m} --deck ${CMAKE_CURRENT_LIST_DIR}/bars_self_${m}.nml
    ${BARS_EQUAL})
endforeach()
# DLM Gauss-Seidel sweeps (all pairs on part 0): every dump bitwise identical
# on 1, 2, 3 and 4 ranks.
impact3d_check(parallel/bitwise_bars_dlm_sweeps "regression;parallel;contact" bitwise
  --workdir ${WORK}/bitwise_bars_dlm_sweeps --deck ${DECKS}/bars_equal_dlm.nml --ranks 1 2 3 4
  --replace "method = 'dlm'" "method = 'dlm', sweeps = 3")
