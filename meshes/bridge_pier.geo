// Bridge pier on an unstable slope (Kestranek & Nedoma 1996, section 11):
// the project's reconstruction of the report's geometry (its figure 11.1 is
// not available), see ../shared/docs/benchmarks.md B1 and
// doc/benchmarks/bridge_pier.md.  Units: m.  Plane strain.
//
// Three bodies, each written to its own .msh file (a dualcontact body is one
// mesh; contact is between bodies, never inside one):
//   body = 1  bedrock (region 1): x in [0,60], from y = 0 up to the ground
//             line (0,8)-(32,8)-(60,22)
//   body = 2  slope mass (region 2): a 4 m thick layer (vertically) on the
//             incline between x = 32 and x = 56
//   body = 3  foundation (region 3) [24,32]x[8,12], pier (region 4)
//             [26,30]x[12,30], deck (region 5) [10,50]x[30,32], glued
//             (one conforming mesh, three material regions)
//
// Physical tags: cells get the region number as material id (1..5); the
// boundary lines get these boundary ids (distinct over all bodies):
//   bedrock:  1 bottom y = 0 (fixed), 2 flat ground under the foundation
//             x in [24,32] (slave of contact 2), 3 incline under the slope
//             mass x in [32,56] (master of contact 1), 4 the other (free)
//             lines
//   slope:    5 slip surface (slave of contact 1), 6 lower end face x = 32
//             (slave of contact 3), 7 up-slope end face x = 56 (prescribed
//             displacement u0), 8 top (free)
//   pier:     9 foundation bottom (master of contact 2), 10 foundation right
//             face x = 32 (master of contact 3), 11 deck top (load P),
//             12 deck left end x = 10 (pinned), 13 deck right end x = 50
//             (roller), 14 the other (free) lines
//
// The app needs quadrilaterals (deal.II): the bedrock is meshed with
// triangles recombined into quads (Blossom), the slope mass and the pier
// body are structured; the report used 551 linear triangles.  Every line is
// divided into a fixed number of segments, times 2^level (transfinite
// lines, even totals so that Blossom leaves no triangle).  The slave lines
// are coarse so that the coarse level has the report's 10 contact nodes
// (5 on the slip surface, 3 under the foundation, 2 on the slope's lower end
// face); the master surfaces of the pier body are finer (1 m cells; the
// meshes need not match).  Coarse level: 360 vertices, 261 quadrilaterals
// (report: 380 vertices, 551 triangles).
//
// Generate (meshes/make_bridge_pier regenerates all nine files):
//   gmsh -2 -format msh22 -setnumber body 1 -setnumber level 0 \
//        bridge_pier.geo -o bridge_pier_body1_level0.msh

DefineConstant[ body = {1, Choices{1, 2, 3}, Name "body"} ];
DefineConstant[ level = {0, Name "refinement level"} ];

f = 2^level;
// target element sizes [m] of the coarse level
lc_rock  = 4.0;   // bedrock away from the contact
lc_slope = 3.4;   // slope mass
lc_found = 1.6;   // foundation
lc_pier  = 1.0;   // pier and deck

Mesh.RecombineAll = 1;
Mesh.RecombinationAlgorithm = 1;  // Blossom
Mesh.Algorithm = 6;               // frontal-Delaunay (then recombined)
Mesh.ElementOrder = 1;
Mesh.SaveAll = 0;                 // only the physical groups
Mesh.MshFileVersion = 2.2;

// number of segments of the slave lines (coarse level: 4 + 2 + 1 segments,
// 5 + 3 + 2 = 10 slave nodes)
n_incline = 4 * f;
n_flat    = 2 * f;
n_end     = 1 * f;

If (body == 1)
  Point(1) = {0, 0, 0, lc_rock / f};
  Point(2) = {60, 0, 0, lc_rock / f};
  Point(3) = {60, 22, 0, lc_rock / f};
  Point(4) = {56, 20, 0, lc_slope / f};
  Point(5) = {32, 8, 0, lc_found / f};
  Point(6) = {24, 8, 0, lc_found / f};
  Point(7) = {0, 8, 0, lc_rock / f};
  Line(1) = {1, 2};
  Line(2) = {2, 3};
  Line(3) = {3, 4};
  Line(4) = {4, 5};   // incline under the slope mass
  Line(5) = {5, 6};   // flat ground under the foundation
  Line(6) = {6, 7};
  Line(7) = {7, 1};
  Transfinite Line{4} = n_incline + 1;
  Transfinite Line{5} = n_flat + 1;
  // every line's division fixed, with an even total, so that Blossom
  // recombines into quadrilaterals only
  Transfinite Line{1} = 20 * f + 1;
  Transfinite Line{2} = 8 * f + 1;
  Transfinite Line{3} = 1 * f + 1;
  Transfinite Line{6} = 8 * f + 1;
  Transfinite Line{7} = 3 * f + 1;
  Curve Loop(1) = {1, 2, 3, 4, 5, 6, 7};
  Plane Surface(1) = {1};
  Physical Surface(1) = {1};
  Physical Line(1) = {1};
  Physical Line(2) = {5};
  Physical Line(3) = {4};
  Physical Line(4) = {2, 3, 6, 7};
EndIf

If (body == 2)
  Point(1) = {32, 8, 0, lc_slope / f};
  Point(2) = {56, 20, 0, lc_slope / f};
  Point(3) = {56, 24, 0, lc_slope / f};
  Point(4) = {32, 12, 0, lc_slope / f};
  Line(1) = {1, 2};   // slip surface
  Line(2) = {2, 3};   // up-slope end face
  Line(3) = {3, 4};   // top
  Line(4) = {4, 1};   // lower end face (against the foundation)
  Transfinite Line{1, 3} = n_incline + 1;
  Transfinite Line{2, 4} = n_end + 1;
  Curve Loop(1) = {1, 2, 3, 4};
  Plane Surface(1) = {1};
  Transfinite Surface{1};
  Physical Surface(2) = {1};
  Physical Line(5) = {1};
  Physical Line(6) = {4};
  Physical Line(7) = {2};
  Physical Line(8) = {3};
EndIf

If (body == 3)
  // foundation
  Point(1) = {24, 8, 0, lc_pier / f};
  Point(2) = {32, 8, 0, lc_pier / f};
  Point(3) = {32, 12, 0, lc_pier / f};
  Point(4) = {30, 12, 0, lc_pier / f};
  Point(5) = {26, 12, 0, lc_pier / f};
  Point(6) = {24, 12, 0, lc_pier / f};
  // pier top = deck bottom
  Point(7) = {30, 30, 0, lc_pier / f};
  Point(8) = {26, 30, 0, lc_pier / f};
  // deck
  Point(9)  = {50, 30, 0, lc_pier / f};
  Point(10) = {50, 32, 0, lc_pier / f};
  Point(11) = {10, 32, 0, lc_pier / f};
  Point(12) = {10, 30, 0, lc_pier / f};
  Line(1) = {1, 2};    // foundation bottom
  Line(2) = {2, 3};    // foundation right face
  Line(3) = {3, 4};
  Line(4) = {4, 5};    // foundation / pier
  Line(5) = {5, 6};
  Line(6) = {6, 1};
  Line(7) = {4, 7};    // pier right
  Line(8) = {7, 8};    // pier / deck
  Line(9) = {8, 5};    // pier left
  Line(10) = {7, 9};   // deck bottom right
  Line(11) = {9, 10};  // deck right end
  Line(12) = {10, 11}; // deck top
  Line(13) = {11, 12}; // deck left end
  Line(14) = {12, 8};  // deck bottom left
  // structured: 1 m cells on the coarse level (the master surfaces of
  // contacts 2 and 3 may be finer than the slave lines)
  Transfinite Line{1} = 8 * f + 1;
  Transfinite Line{2, 6} = 4 * f + 1;
  Transfinite Line{3, 5} = 2 * f + 1;
  Transfinite Line{4, 8} = 4 * f + 1;
  Transfinite Line{7, 9} = 18 * f + 1;
  Transfinite Line{10} = 20 * f + 1;
  Transfinite Line{11, 13} = 2 * f + 1;
  Transfinite Line{12} = 40 * f + 1;
  Transfinite Line{14} = 16 * f + 1;
  Curve Loop(1) = {1, 2, 3, 4, 5, 6};
  Plane Surface(1) = {1};
  Transfinite Surface{1} = {1, 2, 3, 6};
  Curve Loop(2) = {-4, 7, 8, 9};
  Plane Surface(2) = {2};
  Transfinite Surface{2};
  Curve Loop(3) = {-8, 10, 11, 12, 13, 14};
  Plane Surface(3) = {3};
  Transfinite Surface{3} = {12, 9, 10, 11};
  Physical Surface(3) = {1};
  Physical Surface(4) = {2};
  Physical Surface(5) = {3};
  Physical Line(9) = {1};
  Physical Line(10) = {2};
  Physical Line(11) = {12};
  Physical Line(12) = {13};
  Physical Line(13) = {11};
  Physical Line(14) = {3, 5, 6, 7, 9, 10, 14};
EndIf
