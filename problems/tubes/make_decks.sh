#!/bin/sh
# Writes the crossed-tube decks (docs/problems.md, D4, D5): same and 10x stiffer
# struck tube, DLM and DAM. The decks are committed; this records how.
set -e
for variant in same stiff; do
  if [ $variant = same ]; then
    mat_a="&material name = 'al_a', eos = 'mie_gruneisen', library = 'al6061', strength = 'steinberg_guinan' /"
    what="same material (Al 6061-T6)"
    label="same stiffness"
  else
    mat_a="&material name = 'al_a', eos = 'mie_gruneisen', library = 'al6061', c0 = 1.657049,
  strength = 'steinberg_guinan', shear_modulus = 2.76 /"
    what="struck tube 10x stiffer in bulk and shear (c0 x sqrt(10), G0 x 10, same density)"
    label="struck tube 10x stiffer"
  fi
  for method in dlm dam; do
    M=$(echo $method | tr a-z A-Z)
    cat > tubes_${variant}_${method}.nml <<DECK
! Two crossed tubes (docs/problems.md, D4/D5), $M, $what: thick-walled Al 6061-T6
! tubes (outer radius 1 cm, wall 0.2 cm, length 8 cm), axes crossed at 90
! degrees; tube b (axis y, above) moves at 0.002 cm/us (20 m/s) along -z onto
! tube a (axis x, at rest); initial gap 0.05 cm. Quarter symmetry (x >= 0,
! y >= 0): each tube is half its length and half its section. Mie-Gruneisen +
! Steinberg-Guinan (library data). Contact lasts from 26 to 150 us (same
! stiffness); t_end leaves 100 us after the separation. Units cm, g, us, Mbar.
&control title = 'Crossed tubes ($label), $M', t_end = 260.0 /
&mesh name = 'a', type = 'tube', ri = 0.8, ro = 1.0, length = 4.0, sector = 'half',
  n_theta = 32, n_radial = 3, n_axial = 40, axis = 1.0, 0.0, 0.0, origin = 0.0, 0.0, 0.0,
  radial_reference = 0.0, 0.0, -1.0, block = 'a' /
&mesh name = 'b', type = 'tube', ri = 0.8, ro = 1.0, length = 4.0, sector = 'half',
  n_theta = 32, n_radial = 3, n_axial = 40, axis = 0.0, 1.0, 0.0, origin = 0.0, 0.0, 2.05,
  radial_reference = 0.0, 0.0, 1.0, block = 'b' /
$mat_a
&material name = 'al_b', eos = 'mie_gruneisen', library = 'al6061', strength = 'steinberg_guinan' /
&block name = 'a', material = 'al_a' /
&block name = 'b', material = 'al_b' /
&region block = 'a', density = 2.703, energy = 0.0 /
&region block = 'b', density = 2.703, energy = 0.0, velocity = 0.0, 0.0, -0.002 /
&boundary set = 'a_bottom', type = 'symmetry' /
&boundary set = 'a_ysym', type = 'symmetry' /
&boundary set = 'b_bottom', type = 'symmetry' /
&boundary set = 'b_ysym', type = 'symmetry' /
&contact name = 'cross', surface_a = 'b_outer', surface_b = 'a_outer', method = '$method' /
&output status_every = 2000, dump_interval = 20.0 /
DECK
  done
done
