// Projectile for tests/regression/cases/gmsh_two_parts: a 0.6 x 0.6 x 0.4 cm
// block of 6 x 6 x 4 hexahedra (extruded with layers and recombined), centred
// over the plate, 0.02 cm above it. Mesh: gmsh -3 -format msh41 projectile.geo
Point(1) = {0.2, 0.2, 0.52};
l[] = Extrude {0.6, 0, 0} { Point{1}; Layers{6}; Recombine; };
s[] = Extrude {0, 0.6, 0} { Line{l[1]}; Layers{6}; Recombine; };
v[] = Extrude {0, 0, 0.4} { Surface{s[1]}; Layers{4}; Recombine; };
Physical Volume("projectile") = {v[1]};
Physical Surface("bottom") = {s[1]};
Physical Surface("top") = {v[0]};
