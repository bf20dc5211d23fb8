// Quarter of the Taylor rod (problems/taylor_contact: OFHC copper, radius
// 0.955 cm, length 7.51 cm) meshed by gmsh as the built-in 'rod' generator
// meshes it (coarse: a square core 5 x 5 up to 0.55 R, an O-grid ring of 4
// zones to the circle, 60 zones along the axis; the core and the ring are
// transfinite and recombined, the volume extruded in layers), for
// make_mesh.py, which writes rod_quarter.exo (Exodus II).
R = 0.955; f = 0.55; a = f * R; L = 7.51;
nc = 5; nr = 4; nz = 60;
Point(1) = {0, 0, 0}; Point(2) = {a, 0, 0}; Point(3) = {a, a, 0}; Point(4) = {0, a, 0};
Point(5) = {R, 0, 0}; Point(6) = {R * Cos(Pi / 4), R * Sin(Pi / 4), 0}; Point(7) = {0, R, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(5) = {2, 5}; Circle(6) = {5, 1, 6}; Line(7) = {6, 3};
Circle(8) = {6, 1, 7}; Line(9) = {7, 4};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, 7, -2}; Plane Surface(2) = {2};
Curve Loop(3) = {-7, 8, 9, -3}; Plane Surface(3) = {3};
Transfinite Curve{1, 2, 3, 4, 6, 8} = nc + 1;
Transfinite Curve{5, 7, 9} = nr + 1;
Transfinite Surface{1, 2, 3};
Recombine Surface{1, 2, 3};
v[] = Extrude {0, 0, L} { Surface{1, 2, 3}; Layers{nz}; Recombine; };
// v[]: per surface, the top, the volume and the four sides in curve order.
Physical Volume("rod") = {v[1], v[7], v[13]};
Physical Surface("rod_bottom") = {1, 2, 3};
Physical Surface("rod_top") = {v[0], v[6], v[12]};
Physical Surface("rod_side") = {v[9], v[15]};
Physical Surface("rod_y0") = {v[2], v[8]};
Physical Surface("rod_x0") = {v[5], v[16]};
