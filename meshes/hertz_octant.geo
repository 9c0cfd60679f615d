// The Hertz body of inputs/hertz_3d.prm in tetrahedra (issue 45): the lower
// octant x >= 0, y >= 0, z <= 0 of the ball of radius 1 about the origin,
// graded towards its lowest point (0, 0, -1), where it touches the plane:
// element size h_min within r_min of that point, growing linearly to h_max
// at r_max.
//   gmsh -3 -format msh41 meshes/hertz_octant.geo \
//        -o meshes/hertz_octant.msh
// Physical tags as the quarter ball generator's boundary ids: 0 the sphere,
// 1 the cut x = 0, 2 the flat top z = 0, 3 the cut y = 0; volume 0.
SetFactory("OpenCASCADE");
DefineConstant[ h_min = {0.008, Name "size at the contact point"} ];
DefineConstant[ h_max = {0.15, Name "size away from it"} ];
DefineConstant[ r_min = {0.2, Name "radius of the fine zone"} ];
DefineConstant[ r_max = {0.8, Name "radius where the size is h_max"} ];
ball = newv; Sphere(ball) = {0, 0, 0, 1};
box = newv; Box(box) = {0, 0, -1, 1, 1, 1};
octant() = BooleanIntersection{ Volume{ball}; Delete; }{ Volume{box}; Delete; };

bottom = newp; Point(bottom) = {0, 0, -1};
Field[1] = Distance; Field[1].PointsList = {bottom};
Field[2] = Threshold; Field[2].InField = 1;
Field[2].SizeMin = h_min; Field[2].SizeMax = h_max;
Field[2].DistMin = r_min; Field[2].DistMax = r_max;
Background Field = 2;
Mesh.CharacteristicLengthExtendFromBoundary = 0;
Mesh.CharacteristicLengthFromPoints = 0;
Mesh.ElementOrder = 1;

eps = 1e-6;
x0() = Surface In BoundingBox{-eps, -eps, -1 - eps, eps, 1 + eps, eps};
y0() = Surface In BoundingBox{-eps, -eps, -1 - eps, 1 + eps, eps, eps};
z0() = Surface In BoundingBox{-eps, -eps, -eps, 1 + eps, 1 + eps, eps};
all() = Boundary{ Volume{octant()}; };
sphere() = {};
For i In {0 : #all() - 1}
  s = Abs(all(i));
  If (s != x0(0) && s != y0(0) && s != z0(0))
    sphere() += {s};
  EndIf
EndFor
Physical Volume(0) = {octant()};
Physical Surface(0) = {sphere()};
Physical Surface(1) = {x0()};
Physical Surface(2) = {z0()};
Physical Surface(3) = {y0()};
