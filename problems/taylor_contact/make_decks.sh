#!/bin/sh
# Writes the Taylor-anvil contact decks (docs/problems.md, D7): case 1 and 2, steel
# and 100x stiffer anvil, DLM and DAM, coarse and fine rod mesh. Run from this
# directory; the decks are committed, this only documents how they were made.
set -e
for case in 1 2; do
  if [ $case = 1 ]; then r=0.955; l=7.51; v=0.0083; t=149; else r=0.945; l=7.50; v=0.0205; t=200; fi
  for anvil in steel stiff; do
    if [ $anvil = steel ]; then
      mat="&material name = 'ss', eos = 'mie_gruneisen', library = 'ss304', strength = 'steinberg_guinan' /"
      what="304 stainless steel anvil (Steinberg-Guinan + Mie-Gruneisen, library data)"
    else
      mat="&material name = 'ss', eos = 'mie_gruneisen', library = 'ss304', c0 = 4.57,
  strength = 'elastic_plastic', shear_modulus = 77.0, yield_stress = 1.0 /"
      what="anvil 100x stiffer than 304 SS (bulk and shear x100: c0 x 10, G x 100; elastic)"
    fi
    for method in dlm dam; do
      for mesh in coarse fine; do
        if [ $mesh = coarse ]; then rod="n_core = 5, n_radial = 4, n_axial = 60"; an="nx = 16, ny = 16, nz = 10"
        else rod="n_core = 8, n_radial = 6, n_axial = 96"; an="nx = 24, ny = 24, nz = 15"; fi
        cat > taylor_case${case}_${anvil}_${method}_${mesh}.nml <<DECK
! Taylor anvil case $case (docs/problems.md, D7) with contact ($(echo $method | tr a-z A-Z)): OFHC copper rod,
! radius $r cm, length $l cm, at $v cm/us onto a
! $what,
! quarter 3 x 3 x 2 cm (graded: smallest zones under the rod) resting on a
! rigid unilateral wall; the rod starts touching the anvil. Quarter symmetry,
! $mesh rod mesh; final shape at $t us after impact. Units cm, g, us, Mbar.
&control title = 'Taylor case $case, $anvil anvil, $(echo $method | tr a-z A-Z), $mesh', t_end = $t.0 /
&mesh name = 'rod', type = 'rod', radius = $r, length = $l, sector = 'quarter',
  $rod, block = 'rod' /
&mesh name = 'anvil', x = 0.0, 3.0, y = 0.0, 3.0, z = -2.0, 0.0, $an,
  ratio_x = 3.0, ratio_y = 3.0, ratio_z = 0.333333333333, block = 'anvil' /
&material name = 'cu', eos = 'mie_gruneisen', library = 'cu_taylor', strength = 'steinberg_guinan' /
$mat
&block name = 'rod', material = 'cu' /
&block name = 'anvil', material = 'ss' /
&region block = 'rod', density = 8.93, energy = 0.0, velocity = 0.0, 0.0, -$v /
&region block = 'anvil', density = 7.90, energy = 0.0 /
&boundary set = 'xsym', type = 'symmetry' /
&boundary set = 'ysym', type = 'symmetry' /
&boundary set = 'xmin', type = 'symmetry' /
&boundary set = 'ymin', type = 'symmetry' /
&boundary set = 'anvil_zmin', type = 'wall' /
&contact name = 'foot', surface_a = 'rod_bottom', surface_b = 'anvil_zmax', method = '$method' /
&output status_every = 5000, dump_interval = $t.0 /
DECK
      done
    done
  done
done
