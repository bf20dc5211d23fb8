// Two separate hexahedral bodies for tests/regression/cases/exodus_import
// (make_mesh.py meshes this with gmsh, then writes Exodus II with meshio and
// netCDF4): a target 1 x 1 x 0.5 cm (6 x 6 x 3 hexahedra) and an impactor
// 0.6 x 0.6 x 0.4 cm (5 x 5 x 4) centred over it, 0.02 cm above; the meshes
// do not match at the interface. Hexahedra by extrusion with layers and
// recombination (a transfinite, recombined mesh).
Point(1) = {0, 0, 0};
a[] = Extrude {1, 0, 0} { Point{1}; Layers{6}; Recombine; };
b[] = Extrude {0, 1, 0} { Line{a[1]}; Layers{6}; Recombine; };
c[] = Extrude {0, 0, 0.5} { Surface{b[1]}; Layers{3}; Recombine; };
Point(100) = {0.2, 0.2, 0.52};
d[] = Extrude {0.6, 0, 0} { Point{100}; Layers{5}; Recombine; };
e[] = Extrude {0, 0.6, 0} { Line{d[1]}; Layers{5}; Recombine; };
f[] = Extrude {0, 0, 0.4} { Surface{e[1]}; Layers{4}; Recombine; };
Physical Volume("target") = {c[1]};
Physical Volume("impactor") = {f[1]};
Physical Surface("target_bottom") = {b[1]};
Physical Surface("target_top") = {c[0]};
Physical Surface("impactor_bottom") = {e[1]};
Physical Surface("impactor_top") = {f[0]};
// The target's four lateral faces, one set each (every Exodus side number
// then occurs in some side set).
Physical Surface("target_side_a") = {c[2]};
Physical Surface("target_side_b") = {c[3]};
Physical Surface("target_side_c") = {c[4]};
Physical Surface("target_side_d") = {c[5]};
