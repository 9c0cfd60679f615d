// The floating cylinder of B5 (inputs/cylinder_p1.prm) in linear triangles,
// as the thesis meshed it (MESH2D; Pospisil 2015, section 3.2.2: n = 660
// unknowns): a disc of radius R = 2.18 m about (R, R) with 64 boundary
// segments and interior triangles of at most 0.26 m: 326 vertices, 652 unknowns.
//   gmsh -2 -format msh22 meshes/cylinder_p1.geo -o meshes/cylinder_p1.msh
// Physical tags: line 1 the circle (both walls' slave boundary), surface 1.
R = 2.18;
lc = 0.26;
n_boundary = 64;
Point(1) = {R, R, 0, lc};
Point(2) = {2 * R, R, 0, lc};
Point(3) = {R, 2 * R, 0, lc};
Point(4) = {0, R, 0, lc};
Point(5) = {R, 0, 0, lc};
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Circle(3) = {4, 1, 5};
Circle(4) = {5, 1, 2};
Transfinite Line{1, 2, 3, 4} = n_boundary / 4 + 1;
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Mesh.Algorithm = 6;
Mesh.CharacteristicLengthExtendFromBoundary = 0;
Mesh.CharacteristicLengthMax = lc;
Mesh.ElementOrder = 1;
Physical Line(1) = {1, 2, 3, 4};
Physical Surface(1) = {1};
