// Test mesh for tests/unit/test_mesh_gmsh.f90: the box [0,2] x [0,1.5] x [0,1]
// cut at x = 1 into two volumes, each meshed with 2 x 2 x 2 hexahedra
// (16 hexahedra, 45 nodes), graded in y so the zones are not all alike.
// Blocks: 3D groups "left" (x < 1, tag 5) and "right" (x > 1, tag 7).
// Face sets: 2D groups "zmax" (z = 1, tag 1), "xmin" (x = 0, tag 5) and the
// interior interface "middle" (x = 1, tag 9).
// A 1D and a 0D group check that the reader ignores them.
// Regenerate (Debian package gmsh):
//   gmsh box_blocks.geo -3 -format msh22 -o box_blocks_v22.msh
//   gmsh box_blocks.geo -3 -format msh41 -o box_blocks_v41.msh
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1.5, 1};
Box(2) = {1, 0, 0, 1, 1.5, 1};
BooleanFragments{ Volume{1}; Delete; }{ Volume{2}; Delete; }
eps = 1e-6;
Transfinite Curve{:} = 3;
ycurves() = Curve In BoundingBox{-eps, -eps, -eps, 2 + eps, 1.5 + eps, eps};
ycurves() += Curve In BoundingBox{-eps, -eps, 1 - eps, 2 + eps, 1.5 + eps, 1 + eps};
For i In {0 : #ycurves() - 1}
  bb() = BoundingBox Curve{ycurves(i)};
  If (bb(4) - bb(1) > 0.5)
    Transfinite Curve{ycurves(i)} = 3 Using Progression 1.4;
  EndIf
EndFor
Transfinite Surface{:};
Recombine Surface{:};
Transfinite Volume{:};
left() = Volume In BoundingBox{-eps, -eps, -eps, 1 + eps, 1.5 + eps, 1 + eps};
right() = Volume In BoundingBox{1 - eps, -eps, -eps, 2 + eps, 1.5 + eps, 1 + eps};
Physical Volume("left", 5) = {left()};
Physical Volume("right", 7) = {right()};
Physical Surface("zmax", 1) =
  Surface In BoundingBox{-eps, -eps, 1 - eps, 2 + eps, 1.5 + eps, 1 + eps};
Physical Surface("xmin", 5) =
  Surface In BoundingBox{-eps, -eps, -eps, eps, 1.5 + eps, 1 + eps};
Physical Surface("middle", 9) =
  Surface In BoundingBox{1 - eps, -eps, -eps, 1 + eps, 1.5 + eps, 1 + eps};
Physical Curve("edge", 1) = Curve In BoundingBox{-eps, -eps, -eps, 2 + eps, eps, eps};
Physical Point("origin", 1) = Point In BoundingBox{-eps, -eps, -eps, eps, eps, eps};
