#!/bin/sh
# Writes the parallel-axis tube decks (docs/problems.md, D4 variant, mirror test):
# two identical Al tubes side by side hitting each other at equal and opposite
# speeds through contact (DLM, DAM), and one of them on a rigid plane wall at
# the mirror plane z = 0. The decks are committed; this records how.
# (make_decks.sh writes the crossed-tube decks; it is unchanged.)
set -e
common_header() {
  cat <<HEAD
! Parallel-axis tubes (docs/problems.md, D4 variant, mirror test): thick-walled Al
! 6061-T6 tubes (outer radius 1 cm, wall 0.2 cm, length 8 cm), axes along x.
! Mie-Gruneisen + Steinberg-Guinan (library data), as tubes_same_*.
! Quarter model: symmetry planes x = 0 (mid-length) and y = 0 (through the
! axes); 32 zones around the half section, 3 across the wall, 40 along the
! half length. The mirror plane is z = 0; the tubes' outer surfaces start
! 0.005 cm from it (gap 0.01 cm) and close at 0.001 cm/us each (relative
! 0.002 cm/us = 20 m/s, as D4). A fixed step (dt_max below the CFL limit all
! run) keeps the contact and wall runs on the same steps. Units cm, g, us, Mbar.
HEAD
}
tube_b="&mesh name = 'b', type = 'tube', ri = 0.8, ro = 1.0, length = 4.0, sector = 'half',
  n_theta = 32, n_radial = 3, n_axial = 40, axis = 1.0, 0.0, 0.0, origin = 0.0, 0.0, 1.005,
  radial_reference = 0.0, 0.0, -1.0, block = 'b' /"
tube_a="&mesh name = 'a', type = 'tube', ri = 0.8, ro = 1.0, length = 4.0, sector = 'half',
  n_theta = 32, n_radial = 3, n_axial = 40, axis = 1.0, 0.0, 0.0, origin = 0.0, 0.0, -1.005,
  radial_reference = 0.0, 0.0, -1.0, block = 'a' /"
material="&material name = 'al', eos = 'mie_gruneisen', library = 'al6061', strength = 'steinberg_guinan' /"
control="t_end = 80.0, dt_max = 0.025"
output="&output status_every = 500, dump_interval = 10.0 /"

for method in dlm dam; do
  M=$(echo $method | tr a-z A-Z)
  {
    common_header
    cat <<DECK
! $M: tube b (above, the body; its mesh comes first so its nodes are numbered
! as in tubes_parallel_wall.nml) moves along -z, tube a (its mirror image
! below) along +z; contact pair 'side' (DAM: tube a is the master). By mirror
! symmetry the contact must act as the rigid frictionless unilateral wall of
! tubes_parallel_wall.nml.
&control title = 'Parallel tubes (mirror test), $M', $control /
$tube_b
$tube_a
$material
&block name = 'b', material = 'al' /
&block name = 'a', material = 'al' /
&region block = 'b', density = 2.703, energy = 0.0, velocity = 0.0, 0.0, -0.001 /
&region block = 'a', density = 2.703, energy = 0.0, velocity = 0.0, 0.0, 0.001 /
&boundary set = 'b_bottom', type = 'symmetry' /
&boundary set = 'b_ysym', type = 'symmetry' /
&boundary set = 'a_bottom', type = 'symmetry' /
&boundary set = 'a_ysym', type = 'symmetry' /
&contact name = 'side', surface_a = 'b_outer', surface_b = 'a_outer', method = '$method' /
$output
DECK
  } > tubes_parallel_${method}.nml
done
{
  common_header
  cat <<DECK
! Wall reference: tube b alone on the rigid frictionless unilateral wall given
! by the plane z = 0 (wall_point, wall_normal), which its outer surface reaches
! at t = 5 us.
&control title = 'Parallel tubes (mirror test), tube on the wall', $control /
$tube_b
$material
&block name = 'b', material = 'al' /
&region block = 'b', density = 2.703, energy = 0.0, velocity = 0.0, 0.0, -0.001 /
&boundary set = 'b_bottom', type = 'symmetry' /
&boundary set = 'b_ysym', type = 'symmetry' /
&boundary set = 'b_outer', type = 'wall', wall_point = 0.0, 0.0, 0.0, wall_normal = 0.0, 0.0, 1.0 /
$output
DECK
} > tubes_parallel_wall.nml
