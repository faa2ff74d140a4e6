// A steel hemisphere on an aluminium block (Hertz between two different materials), as quarter
// models (x >= 0, y >= 0). Drawn in millimetres: read it with [mesh] unit = "mm".
//   "ball":  the lower half of the sphere of radius R centred at (0, 0, +R), its pole at the
//            origin pointing down, its flat face on z = +R;
//   "block": the quarter of a 100 x 100 x 50 block: x and y in [0, 50], z in [-50, 0]; its top
//            face z = 0 touches the pole at the origin.
// The volumes are two separate OpenCASCADE solids, never fragmented together: they share no
// point, curve or surface, so Gmsh meshes them as two bodies without common nodes, and the
// ball's curved surface and the block's top get their own, non-matching meshes (different
// element sizes near the origin).
SetFactory("OpenCASCADE");
R = 50;          // radius of the hemisphere [mm]
L = 50;          // half width of the block (the quarter's x and y extent) [mm]
T = 50;          // thickness of the block [mm]
h_ball = 0.3;    // element size in the ball near the pole [mm]
h_block = 0.4;   // element size in the block near the origin [mm]
h_far = 8;       // element size far from the contact [mm]
d_fine = 7;      // the fine sizes hold up to this distance from the origin [mm]
d_coarse = 45;   // and grow linearly to h_far at this distance [mm]
e = 1e-3;        // tolerance of the bounding-box searches [mm]

// Sphere(tag) = {xc, yc, zc, radius, latitude from, latitude to, azimuth range}
Sphere(1) = {0, 0, R, R, -Pi/2, 0, Pi/2};    // southern half, one quarter in azimuth
Box(2) = {0, 0, -T, L, L, T};

Physical Volume("ball") = {1};
Physical Volume("block") = {2};

// The ball's faces.
ball_top() = Surface In BoundingBox{-e, -e, R - e, R + e, R + e, R + e};
ball_sx()  = Surface In BoundingBox{-e, -e, -e, e, R + e, R + e};      // the plane x = 0
ball_sy()  = Surface In BoundingBox{-e, -e, -e, R + e, e, R + e};      // the plane y = 0
ball_c()   = Abs(Boundary{ Volume{1}; });
ball_c()  -= ball_top();
ball_c()  -= ball_sx();
ball_c()  -= ball_sy();
// The block's faces (the box's faces lie in the planes z = 0, z = -T, x = 0, y = 0, ...).
block_top() = Surface In BoundingBox{-e, -e, -e, L + e, L + e, e};
block_bot() = Surface In BoundingBox{-e, -e, -T - e, L + e, L + e, -T + e};
block_sx()  = Surface In BoundingBox{-e, -e, -T - e, e, L + e, e};
block_sy()  = Surface In BoundingBox{-e, -e, -T - e, L + e, e, e};

Physical Surface("ball_contact") = {ball_c()};
Physical Surface("ball_top") = {ball_top()};
Physical Surface("ball_sym_x") = {ball_sx()};
Physical Surface("ball_sym_y") = {ball_sy()};
Physical Surface("block_top") = {block_top()};
Physical Surface("block_bottom") = {block_bot()};
Physical Surface("block_sym_x") = {block_sx()};
Physical Surface("block_sym_y") = {block_sy()};

// Sizes, by the distance from the origin: h_block within d_fine, growing to h_far at d_coarse
// (field 2, everywhere), and h_ball likewise but restricted to the ball and its boundary
// (field 4); the mesh takes the smaller of the two.
Field[1] = MathEval; Field[1].F = "sqrt(x*x + y*y + z*z)";
Field[2] = Threshold; Field[2].InField = 1; Field[2].SizeMin = h_block; Field[2].SizeMax = h_far;
Field[2].DistMin = d_fine; Field[2].DistMax = d_coarse;
Field[3] = Threshold; Field[3].InField = 1; Field[3].SizeMin = h_ball; Field[3].SizeMax = h_far;
Field[3].DistMin = d_fine; Field[3].DistMax = d_coarse;
ball_curves() = Abs(Boundary{ Surface{ Abs(Boundary{ Volume{1}; }) }; });
Field[4] = Restrict; Field[4].InField = 3; Field[4].VolumesList = {1};
Field[4].SurfacesList = {Abs(Boundary{ Volume{1}; })}; Field[4].CurvesList = {ball_curves()};
Field[5] = Min; Field[5].FieldsList = {2, 4};
Background Field = 5;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
