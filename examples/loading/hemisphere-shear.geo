// A steel hemisphere on a steel block, as half models (y >= 0; the shear along x keeps the plane
// y = 0 a plane of symmetry). Drawn in millimetres: read it with [mesh] unit = "mm".
//   "ball":  the lower half of the sphere of radius R centred at (0, 0, +R), its pole at the
//            origin pointing down, its flat face on z = +R;
//   "block": the half of a 100 x 100 x 50 block: x in [-50, 50], y in [0, 50], z in [-50, 0];
//            its top face z = 0 touches the pole at the origin.
// Two separate OpenCASCADE solids (no common nodes): the ball's curved surface and the block's
// top get their own, non-matching meshes.
SetFactory("OpenCASCADE");
R = 50;          // radius of the hemisphere [mm]
L = 50;          // half width of the block [mm]
T = 50;          // thickness of the block [mm]
h_ball = 0.21;   // element size in the ball near the pole [mm]
h_block = 0.28;  // element size in the block near the origin [mm]
h_far = 8;       // element size far from the contact [mm]
d_fine = 7;      // the fine sizes hold up to this distance from the origin [mm]
d_coarse = 45;   // and grow linearly to h_far at this distance [mm]
e = 1e-3;        // tolerance of the bounding-box searches [mm]

// Sphere(tag) = {xc, yc, zc, radius, latitude from, latitude to, azimuth range}
Sphere(1) = {0, 0, R, R, -Pi/2, 0, Pi};      // southern half, half in azimuth (y >= 0)
Box(2) = {-L, 0, -T, 2 * L, L, T};

Physical Volume("ball") = {1};
Physical Volume("block") = {2};

ball_top() = Surface In BoundingBox{-R - e, -e, R - e, R + e, R + e, R + e};
ball_sy()  = Surface In BoundingBox{-R - e, -e, -e, R + e, e, R + e};   // the plane y = 0
ball_c()   = Abs(Boundary{ Volume{1}; });
ball_c()  -= ball_top();
ball_c()  -= ball_sy();
block_top() = Surface In BoundingBox{-L - e, -e, -e, L + e, L + e, e};
block_bot() = Surface In BoundingBox{-L - e, -e, -T - e, L + e, L + e, -T + e};
block_sy()  = Surface In BoundingBox{-L - e, -e, -T - e, L + e, e, e};

Physical Surface("ball_contact") = {ball_c()};
Physical Surface("ball_top") = {ball_top()};
Physical Surface("ball_sym_y") = {ball_sy()};
Physical Surface("block_top") = {block_top()};
Physical Surface("block_bottom") = {block_bot()};
Physical Surface("block_sym_y") = {block_sy()};

// Sizes by the distance from the origin (as examples/two-bodies/sphere-on-block.geo).
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
