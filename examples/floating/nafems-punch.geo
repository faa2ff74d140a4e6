// The NAFEMS punch with rounded edges (Konter, "Advanced finite element contact benchmarks",
// NAFEMS 2006, benchmark 2), as quarter models (x >= 0, y >= 0; both bodies are solids of
// revolution about the z axis). Drawn in millimetres: read it with [mesh] unit = "mm".
//   "punch":      a cylinder of diameter 100 and height 100, z in [0, 100], whose bottom edge is
//                 rounded to radius 10: its bottom is the flat disc r <= 40 on the plane z = 0,
//                 then the quarter torus of the fillet (centre line r = 40, z = 10) up to the
//                 side r = 50 at z = 10;
//   "foundation": a cylinder of diameter 200 and height 200, z in [-200, 0]; its top z = 0
//                 touches the punch's flat disc (zero gap on r <= 40, the fillet lifts off it).
// The punch is the profile (r, z) = (0, 0) - (40, 0) - fillet - (50, 10) - (50, 100) - (0, 100),
// drawn in the plane y = 0 and revolved by 90 degrees about the z axis. The volumes are two
// separate OpenCASCADE solids, never fragmented together: they share no point, curve or surface
// (the punch's flat disc and the foundation's top lie in the same plane but are two surfaces),
// so Gmsh meshes them as two bodies without common nodes, with non-matching meshes at the
// interface (different element sizes near the edge of the flat).
SetFactory("OpenCASCADE");
Rp = 50;          // radius of the punch [mm]
Hp = 100;         // height of the punch [mm]
rf = 10;          // radius of the rounded edge [mm]
Rf = 100;         // radius of the foundation [mm]
Hf = 200;         // height of the foundation [mm]
h_punch = 0.6;    // element size in the punch near the edge of the flat, r = 40, z = 0 [mm]
h_found = 0.8;    // element size in the foundation there [mm]
h_far = 14;       // element size far from it [mm]
h_top = 3;        // element size on the punch's top, so that its facets keep its area [mm]
d_fine = 3;       // the fine sizes hold up to this distance from that circle [mm]
d_coarse = 45;    // and grow linearly to h_far at this distance [mm]
e = 1e-3;         // tolerance of the bounding-box searches [mm]

// The punch's profile in the plane y = 0 (x plays r), revolved about the z axis.
Point(1) = {0, 0, 0};
Point(2) = {Rp - rf, 0, 0};
Point(3) = {Rp - rf, 0, rf};      // centre of the fillet's arc
Point(4) = {Rp, 0, rf};
Point(5) = {Rp, 0, Hp};
Point(6) = {0, 0, Hp};
Line(1) = {1, 2};
Circle(2) = {2, 3, 4};
Delete { Point{3}; }              // the centre is no point of the punch: no node of its own
Line(3) = {4, 5};
Line(4) = {5, 6};
Line(5) = {6, 1};
Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};
punch() = Extrude{ {0, 0, 1}, {0, 0, 0}, Pi/2 }{ Surface{1}; };   // punch(1): the volume
Cylinder(100) = {0, 0, -Hf, 0, 0, Hf, Rf, Pi/2};                   // the foundation's quarter

Physical Volume("punch") = {punch(1)};
Physical Volume("foundation") = {100};

// The punch's faces.
p_all() = Abs(Boundary{ Volume{punch(1)}; });
p_top() = Surface In BoundingBox{-e, -e, Hp - e, Rp + e, Rp + e, Hp + e};
p_c()   = Surface In BoundingBox{-e, -e, -e, Rp + e, Rp + e, rf + e};      // flat disc + fillet
p_sx()  = Surface In BoundingBox{-e, -e, -e, e, Rp + e, Hp + e};           // the plane x = 0
p_sy()  = Surface In BoundingBox{-e, -e, -e, Rp + e, e, Hp + e};           // the plane y = 0
// The foundation's faces (the punch's disc lies in the plane z = 0 too: take it out).
f_top() = Surface In BoundingBox{-e, -e, -e, Rf + e, Rf + e, e};
f_top() -= p_all();
f_bot() = Surface In BoundingBox{-e, -e, -Hf - e, Rf + e, Rf + e, -Hf + e};
f_sx()  = Surface In BoundingBox{-e, -e, -Hf - e, e, Rf + e, e};
f_sx() -= p_all();
f_sy()  = Surface In BoundingBox{-e, -e, -Hf - e, Rf + e, e, e};
f_sy() -= p_all();

Physical Surface("punch_contact") = {p_c()};
Physical Surface("punch_top") = {p_top()};
Physical Surface("punch_sym_x") = {p_sx()};
Physical Surface("punch_sym_y") = {p_sy()};
Physical Surface("foundation_top") = {f_top()};
Physical Surface("foundation_bottom") = {f_bot()};
Physical Surface("foundation_sym_x") = {f_sx()};
Physical Surface("foundation_sym_y") = {f_sy()};

// Sizes, by the distance from the circle r = 40, z = 0 (the edge of the flat, where the contact
// pressure peaks): h_found within d_fine, growing to h_far at d_coarse (field 2, everywhere),
// and h_punch likewise but restricted to the punch and its boundary (field 4); besides, h_top on
// the punch's top, growing to h_far 30 mm below it (field 7, in the punch only): the loaded face
// is a polygon, and with h_far its area (hence the applied force) would be 1 % short, with
// h_top 0.1 %. The mesh takes the smallest of them.
Field[1] = MathEval; Field[1].F = Sprintf("sqrt((sqrt(x*x + y*y) - %g)^2 + z*z)", Rp - rf);
Field[2] = Threshold; Field[2].InField = 1; Field[2].SizeMin = h_found; Field[2].SizeMax = h_far;
Field[2].DistMin = d_fine; Field[2].DistMax = d_coarse;
Field[3] = Threshold; Field[3].InField = 1; Field[3].SizeMin = h_punch; Field[3].SizeMax = h_far;
Field[3].DistMin = d_fine; Field[3].DistMax = d_coarse;
p_curves() = Abs(Boundary{ Surface{ p_all() }; });
Field[4] = Restrict; Field[4].InField = 3; Field[4].VolumesList = {punch(1)};
Field[4].SurfacesList = {p_all()}; Field[4].CurvesList = {p_curves()};
Field[5] = MathEval; Field[5].F = Sprintf("%g - z", Hp);
Field[6] = Threshold; Field[6].InField = 5; Field[6].SizeMin = h_top; Field[6].SizeMax = h_far;
Field[6].DistMin = 0; Field[6].DistMax = 30;
Field[7] = Restrict; Field[7].InField = 6; Field[7].VolumesList = {punch(1)};
Field[7].SurfacesList = {p_all()}; Field[7].CurvesList = {p_curves()};
Field[8] = Min; Field[8].FieldsList = {2, 4, 7};
Background Field = 8;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
