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
// The three contact lines are separate, as the report's "10 - 15, 16 - 11
// and 14 - 17" (six distinct end vertices): the slip surface runs the whole
// incline (32,8)-(56,20); the foundation stands on the ground line only
// between x = 24 and x = 30 (the last metre pair [30,32] at the corner is
// free); the slope's lower end face touches the foundation's right face
// only between y = 10 and y = 12 (its lower part [8,10] is free).  So no
// point belongs to two contact lines, and every contact row acts on its own
// two nodes.
//
// The meshes match along the contact lines (node-to-node rows, as the
// report's: LJA = 40 = 10 rows x 4 entries): both sides of each contact line
// have the same nodes.
//
// Physical tags: cells get the region number as material id (1..5); the
// boundary lines get these boundary ids (distinct over all bodies):
//   bedrock:  1 bottom y = 0 (fixed), 2 flat ground under the foundation
//             x in [24,30] (slave of contact 2), 3 incline under the slope
//             mass x in [32,56] (master of contact 1), 4 the other (free)
//             lines
//   slope:    5 slip surface (slave of contact 1), 6 upper part y in
//             [10,12] of the lower end face x = 32 (slave of contact 3),
//             7 up-slope end face x = 56 (prescribed displacement u0),
//             8 top and the lower part of the end face (free)
//   pier:     9 foundation bottom x in [24,30] (master of contact 2),
//             10 foundation right face y in [10,12] (master of contact 3),
//             11 deck top (load P), 12 deck left end x = 10 (pinned),
//             13 deck right end x = 50 (roller), 14 the other (free) lines
//
// With recombine = 1 (the default) the bedrock and the foundation are
// meshed with triangles recombined into quads (Blossom), the slope mass, the
// pier and the deck are structured quadrilaterals; with recombine = 0 the
// same lines carry linear triangles, as the report's 551 (level 0: 355
// vertices and 516 triangles, the report's 380 and 551; the contact lines,
// which fix the rest, are the report's).
// Every line is divided into a fixed number of segments, times 2^level
// (transfinite lines, even totals per recombined surface so that Blossom
// leaves no triangle).  The contact lines are coarse so that the coarse
// level has the report's 10 contact node pairs (5 on the slip surface, 3
// under the foundation, 2 on the slope's lower end face).
//
// Generate (meshes/make_bridge_pier regenerates all nine files and rounds
// the node coordinates so that the two sides of a contact line agree
// exactly):
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

DefineConstant[ recombine = {1, Choices{0, 1}, Name "recombine into quadrilaterals"} ];
Mesh.RecombineAll = recombine;
Mesh.RecombinationAlgorithm = 1;  // Blossom
Mesh.Algorithm = 6;               // frontal-Delaunay (then recombined)
Mesh.ElementOrder = 1;
Mesh.SaveAll = 0;                 // only the physical groups
Mesh.MshFileVersion = 2.2;

// segments of the contact lines (coarse level: 4 + 2 + 1 segments,
// 5 + 3 + 2 = 10 contact node pairs) and of the free pieces between them
n_incline = 4 * f;   // slip surface (32,8)-(56,20)
n_flat    = 2 * f;   // ground under the foundation (24,8)-(30,8)
n_end     = 1 * f;   // slope end face on the foundation (32,10)-(32,12)
n_gap     = 1 * f;   // free pieces (30,8)-(32,8) and (32,8)-(32,10)

If (body == 1)
  Point(1) = {0, 0, 0, lc_rock / f};
  Point(2) = {60, 0, 0, lc_rock / f};
  Point(3) = {60, 22, 0, lc_rock / f};
  Point(4) = {56, 20, 0, lc_slope / f};
  Point(5) = {32, 8, 0, lc_found / f};
  Point(8) = {30, 8, 0, lc_found / f};
  Point(6) = {24, 8, 0, lc_found / f};
  Point(7) = {0, 8, 0, lc_rock / f};
  Line(1) = {1, 2};
  Line(2) = {2, 3};
  Line(3) = {3, 4};
  Line(4) = {5, 4};   // incline under the slope mass (same direction as the slope's)
  Line(5) = {5, 8};   // free piece of the ground at the corner
  Line(8) = {6, 8};   // ground under the foundation (same direction as the foundation's)
  Line(6) = {6, 7};
  Line(7) = {7, 1};
  Transfinite Line{4} = n_incline + 1;
  Transfinite Line{8} = n_flat + 1;
  Transfinite Line{5} = n_gap + 1;
  // every line's division fixed, with an even total, so that Blossom
  // recombines into quadrilaterals only
  Transfinite Line{1} = 20 * f + 1;
  Transfinite Line{2} = 8 * f + 1;
  Transfinite Line{3} = 1 * f + 1;
  Transfinite Line{6} = 8 * f + 1;
  Transfinite Line{7} = 2 * f + 1;
  Curve Loop(1) = {1, 2, 3, -4, 5, -8, 6, 7};
  Plane Surface(1) = {1};
  Physical Surface(1) = {1};
  Physical Line(1) = {1};
  Physical Line(2) = {8};
  Physical Line(3) = {4};
  Physical Line(4) = {2, 3, 5, 6, 7};
EndIf

If (body == 2)
  Point(1) = {32, 8, 0, lc_slope / f};
  Point(2) = {56, 20, 0, lc_slope / f};
  Point(3) = {56, 24, 0, lc_slope / f};
  Point(4) = {32, 12, 0, lc_slope / f};
  Point(5) = {32, 10, 0, lc_slope / f};
  Line(1) = {1, 2};   // slip surface
  Line(2) = {2, 3};   // up-slope end face
  Line(3) = {3, 4};   // top
  Line(4) = {5, 4};   // upper part of the lower end face (against the foundation)
  Line(5) = {5, 1};   // lower part of the lower end face (free)
  Transfinite Line{1, 3} = n_incline + 1;
  Transfinite Line{4} = n_end + 1;
  Transfinite Line{5} = n_gap + 1;
  Transfinite Line{2} = n_end + n_gap + 1;
  Curve Loop(1) = {1, 2, 3, -4, 5};
  Plane Surface(1) = {1};
  Transfinite Surface{1} = {1, 2, 3, 4};
  Physical Surface(2) = {1};
  Physical Line(5) = {1};
  Physical Line(6) = {4};
  Physical Line(7) = {2};
  Physical Line(8) = {3, 5};
EndIf

If (body == 3)
  // foundation
  Point(1) = {24, 8, 0, lc_pier / f};
  Point(2) = {32, 8, 0, lc_pier / f};
  Point(3) = {32, 12, 0, lc_pier / f};
  Point(4) = {30, 12, 0, lc_pier / f};
  Point(5) = {26, 12, 0, lc_pier / f};
  Point(6) = {24, 12, 0, lc_pier / f};
  Point(15) = {30, 8, 0, lc_pier / f};
  Point(16) = {32, 10, 0, lc_pier / f};
  // pier top = deck bottom
  Point(7) = {30, 30, 0, lc_pier / f};
  Point(8) = {26, 30, 0, lc_pier / f};
  // deck
  Point(9)  = {50, 30, 0, lc_pier / f};
  Point(10) = {50, 32, 0, lc_pier / f};
  Point(11) = {10, 32, 0, lc_pier / f};
  Point(12) = {10, 30, 0, lc_pier / f};
  Line(1) = {1, 15};   // foundation bottom on the ground (contact 2)
  Line(15) = {15, 2};  // foundation bottom at the corner (free)
  Line(16) = {2, 16};  // foundation right face, lower part (free)
  Line(2) = {16, 3};   // foundation right face, upper part (contact 3)
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
  // the contact lines as coarse as their partners' (matching nodes); the
  // foundation is recombined (Blossom, even total: 2+1+2+1+2+4+2+4 = 18),
  // the pier and the deck structured with 1 m cells
  Transfinite Line{1} = n_flat + 1;
  Transfinite Line{15} = n_gap + 1;
  Transfinite Line{16} = 2 * n_gap + 1;
  Transfinite Line{2} = n_end + 1;
  Transfinite Line{6} = 4 * f + 1;
  Transfinite Line{3, 5} = 2 * f + 1;
  Transfinite Line{4, 8} = 4 * f + 1;
  Transfinite Line{7, 9} = 18 * f + 1;
  Transfinite Line{10} = 20 * f + 1;
  Transfinite Line{11, 13} = 2 * f + 1;
  Transfinite Line{12} = 40 * f + 1;
  Transfinite Line{14} = 16 * f + 1;
  Curve Loop(1) = {1, 15, 16, 2, 3, 4, 5, 6};
  Plane Surface(1) = {1};
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
  Physical Line(14) = {3, 5, 6, 7, 9, 10, 14, 15, 16};
EndIf
