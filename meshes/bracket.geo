// An angle bracket (steel): a base plate with a bolt hole and an upright,
// meshed with tetrahedra (what a CAD part meshes to).  Lengths in metres.
//   gmsh -3 -format msh41 bracket.geo -o bracket.msh
// Physical tags: volume 0 (material id 0); surface 1: the underside of the
// base (contact, slave), surface 2: the top of the upright (loaded), every
// other boundary face tag 0 (free).
SetFactory("OpenCASCADE");
base    = newv; Box(base) = {0, 0, 0, 0.06, 0.04, 0.008};
upright = newv; Box(upright) = {0, 0, 0, 0.008, 0.04, 0.05};
hole    = newv; Cylinder(hole) = {0.04, 0.02, -0.001, 0, 0, 0.010, 0.005};
body() = BooleanUnion{ Volume{base}; Delete; }{ Volume{upright}; Delete; };
part() = BooleanDifference{ Volume{body()}; Delete; }{ Volume{hole}; Delete; };

Mesh.CharacteristicLengthMax = 0.003;
Mesh.CharacteristicLengthMin = 0.0015;
Mesh.ElementOrder = 1;

eps = 1e-6;
bottom() = Surface In BoundingBox{-eps, -eps, -eps, 0.06 + eps, 0.04 + eps, eps};
top()    = Surface In BoundingBox{-eps, -eps, 0.05 - eps, 0.008 + eps, 0.04 + eps, 0.05 + eps};
all()    = Boundary{ Volume{part()}; };
Physical Volume(0) = {part()};
Physical Surface(1) = {bottom()};
Physical Surface(2) = {top()};
free() = {};
For i In {0 : #all() - 1}
  s = Abs(all(i));
  If (s != bottom(0) && s != top(0))
    free() += {s};
  EndIf
EndFor
Physical Surface(0) = {free()};
