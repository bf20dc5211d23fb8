# Sedov octant split along the sphere r = 0.5 by contact (docs/problems.md, D2,
# curved split). A ball octant (mesh type 'ball') and the box minus the ball
# ('box_minus_ball') are meshed apart with non-matching patches on the sphere
# (12 against 18 zones along a patch edge on the medium mesh) and joined by the
# pair 'r05'; the shock crosses the interface at t = 0.18 and reaches r = 1 at t
# = 1.
#
# Medium mesh (problems/sedov_contact/sedov_curved_{dlm,dam}_b.nml, 22680
# zones), measured on 2 ranks (problems/sedov_contact/README.md):
#   DLM: L1(rho) 0.1046 = 0.74 x the single-mesh 30^3 run (0.1413), shock
#        +1.27%, max |energy_error| 1.2e-13, contact work -9.4e-4 E0, momentum
#        booked by contact 0 to round-off;
#   DAM (one pass, before 2026-11-27): L1(rho) 0.0706 = 0.50 x, shock +0.77%,
#        max |energy_error| 1.2e-13, contact work -2.0e-2 E0;
#   DAM (two passes + recovery, the defaults since 2026-11-27): L1(rho)
#        0.1038 = 0.74 x, shock +1.23%, |energy_error| 2.6e-16, contact work
#        -7.1e-4 E0, radial penetration 1.2e-3.
# Criteria: L1(rho) at most the single-mesh 30^3 run's (--tol 0: the split
# mesh's spherical patches follow the shock, so the contact run must not be
# worse than the Cartesian single mesh; DLM has 26% margin); shock radius
# within 2% of exact (the single-mesh criterion, both signs); the energy
# balance that books the contact work closes to 1e-12 (round-off over about
# 800 cycles, as energy/sedov_20); both methods: the momentum the contact
# forces add is zero to 1e-12 of the largest |momentum| (DLM's pair forces are
# equal and opposite; DAM returns each slave's defect to its group,
# docs/contact.md section 6). Total momentum is not checked: the symmetry
# planes take reactions. The interface is not asserted in contact on every
# cycle (--pair none): before the shock the surfaces only touch, and nodes
# are released where they do. Each test takes 70-80 s on 2 ranks (contact
# run 45-55 s plus the single-mesh reference), hence the label long.
# The interface itself: in every dump no node of the ball's surface lies more
# than 4e-3 (5% of the gas-side zone size at t = 1, 0.077) radially beyond the
# gas's faceted surface (tools/radial_gap.py: it sees nodes the contact no
# longer holds). Measured: DLM 1.6e-3, DAM 3.1e-3 (both the sagitta of the
# faceting plus a little); DLM without position feedback (recovery = 0)
# let the ball's valence-3 vertex on the diagonal x = y = z escape: 9.4e-2
# at t = 1 on this mesh, 0.45 on the fine one.
foreach(m dlm dam)
  set(SEDOV_CURVED_MOMENTUM --booked-pair r05 --momentum-tol 1e-12)
  impact3d_check(contact/sedov_curved_${m} "long;contact" relative
    --workdir ${WORK}/sedov_curved_${m}
    --deck ${PROBLEMS}/sedov_contact/sedov_curved_${m}_b.nml --reference ${PROBLEMS}/sedov/sedov.nml
    --problem sedov --key L1_rho --tol 0.0 --max shock_r_error_rel=0.02
    --min shock_r_error_rel=-0.02 --energy-tol 1e-12 ${SEDOV_CURVED_MOMENTUM} --pair none --np 2
    --radial-penetration 1 2 0.5 4e-3)
endforeach()

# The curved split on 1, 2 and 3 ranks: every dump bitwise identical (coarse
# mesh, shortened to t = 0.3 so the shock has crossed the interface).
foreach(m dlm dam)
  impact3d_check(parallel/bitwise_sedov_curved_${m} "regression;parallel;contact" bitwise
    --workdir ${WORK}/bitwise_sedov_curved_${m}
    --deck ${PROBLEMS}/sedov_contact/sedov_curved_${m}_a.nml --ranks 1 2 3
    --replace "t_end = 1.0" "t_end = 0.3" --replace "dump_interval = 0.25" "dump_interval = 0.1")
endforeach()

# DAM with its default settings (two passes, recovery) holds both sides of the
# curved split (medium mesh, t = 1, 2 ranks; issue 31 item 3): at every audit
# no node of either surface beyond its default tolerance and none unheld; the
# energy balance with the contact work booked closes to 1e-12; the contact
# work never positive beyond round-off (1e-10 of E0). One pass ended with 20
# ball (master) nodes beyond the tolerance (docs/contact.md, 6.2).
impact3d_check(long/sedov_curved_dam_audit "long;contact" impact
  --workdir ${WORK}/sedov_curved_dam_audit
  --deck ${PROBLEMS}/sedov_contact/sedov_curved_dam_b.nml
  --pair r05 --tol 1e-12 --audit --max-work 1e-10 --np 2)
