// A steel sphere squeezed between two aluminium blocks, as quarter models (x >= 0, y >= 0; every
// body is centred on the z axis). Drawn in millimetres: read it with [mesh] unit = "mm".
//   "lower": the quarter of an 80 x 80 x 20 block: x and y in [0, 40], z in [-20, 0];
//   "ball":  the quarter of the sphere of radius 20 centred at (0, 0, 20): its south pole
//            touches the lower block's top at the origin, its north pole the upper block's
//            bottom at (0, 0, 40);
//   "upper": the quarter of an 80 x 80 x 20 block: x and y in [0, 40], z in [40, 60].
// The sphere is drawn as its two hemispheres (z <= 20 and z >= 20), fragmented together: one
// body (one region, common nodes on the equator's disc) whose curved surface is two boundary
// tags, "ball_bottom" and "ball_top", one for each contact pair. The three bodies are separate
// OpenCASCADE solids, never fragmented with one another: they share no point, curve or surface,
// so Gmsh meshes them as three bodies without common nodes, and each contact pair gets
// non-matching meshes (different element sizes near the poles).
SetFactory("OpenCASCADE");
R = 20;          // radius of the sphere [mm]
L = 40;          // half width of the blocks (the quarter's x and y extent) [mm]
T = 20;          // thickness of the blocks [mm]
h_slave = 0.15;  // element size of the ball's lower half and the upper block's bottom near the poles [mm]
h_master = 0.2;  // element size of the other sides there [mm]
h_far = 4;       // element size far from the contacts [mm]
d_fine = 3;      // the fine sizes hold up to this distance from a pole [mm]
d_coarse = 18;   // and grow linearly to h_far at this distance [mm]
e = 1e-3;        // tolerance of the bounding-box searches [mm]

// Sphere(tag) = {xc, yc, zc, radius, latitude from, latitude to, azimuth range}
Sphere(1) = {0, 0, R, R, -Pi/2, 0, Pi/2};    // southern half, one quarter in azimuth
Sphere(2) = {0, 0, R, R, 0, Pi/2, Pi/2};     // northern half
ball() = BooleanFragments{ Volume{1}; Delete; }{ Volume{2}; Delete; };
Box(10) = {0, 0, -T, L, L, T};               // lower block
Box(11) = {0, 0, 2 * R, L, L, T};            // upper block

Physical Volume("ball") = {ball()};
Physical Volume("lower") = {10};
Physical Volume("upper") = {11};

// The sphere's faces: its curved surface in two halves, and the planes x = 0 and y = 0.
b_all() = Abs(Boundary{ Volume{ball()}; });
b_sx() = Surface In BoundingBox{-e, -e, -e, e, R + e, 2 * R + e};
b_sy() = Surface In BoundingBox{-e, -e, -e, R + e, e, 2 * R + e};
b_bot() = Surface In BoundingBox{-e, -e, -e, R + e, R + e, R + e};
b_bot() -= b_sx();
b_bot() -= b_sy();
b_eq() = Surface In BoundingBox{-e, -e, R - e, R + e, R + e, R + e};
b_bot() -= b_eq();       // the equator's disc is inside the ball: no boundary, no tag
b_top() = Surface In BoundingBox{-e, -e, R - e, R + e, R + e, 2 * R + e};
b_top() -= b_sx();
b_top() -= b_sy();
b_top() -= b_eq();
// The blocks' faces (each block's top or bottom lies in a plane that a pole touches: the pole
// is a point of the sphere, never a surface, so the boxes below catch the blocks' faces only).
lo_top() = Surface In BoundingBox{-e, -e, -e, L + e, L + e, e};
lo_bot() = Surface In BoundingBox{-e, -e, -T - e, L + e, L + e, -T + e};
lo_sx()  = Surface In BoundingBox{-e, -e, -T - e, e, L + e, e};
lo_sy()  = Surface In BoundingBox{-e, -e, -T - e, L + e, e, e};
up_bot() = Surface In BoundingBox{-e, -e, 2 * R - e, L + e, L + e, 2 * R + e};
up_top() = Surface In BoundingBox{-e, -e, 2 * R + T - e, L + e, L + e, 2 * R + T + e};
up_sx()  = Surface In BoundingBox{-e, -e, 2 * R - e, e, L + e, 2 * R + T + e};
up_sy()  = Surface In BoundingBox{-e, -e, 2 * R - e, L + e, e, 2 * R + T + e};

Physical Surface("ball_bottom") = {b_bot()};
Physical Surface("ball_top") = {b_top()};
Physical Surface("ball_sym_x") = {b_sx()};
Physical Surface("ball_sym_y") = {b_sy()};
Physical Surface("lower_top") = {lo_top()};
Physical Surface("lower_bottom") = {lo_bot()};
Physical Surface("lower_sym_x") = {lo_sx()};
Physical Surface("lower_sym_y") = {lo_sy()};
Physical Surface("upper_bottom") = {up_bot()};
Physical Surface("upper_top") = {up_top()};
Physical Surface("upper_sym_x") = {up_sx()};
Physical Surface("upper_sym_y") = {up_sy()};

// Sizes, by the distance from each pole: the ball at the south pole and the upper block at the
// north pole get h_slave, the other side h_master, within d_fine,
// growing to h_far at d_coarse. Fields 3 and 4 (h_master) act everywhere; fields 6 and 8
// (h_slave) are restricted to the ball and to the upper block, with their boundaries; the mesh
// takes the smallest.
Field[1] = MathEval; Field[1].F = "sqrt(x*x + y*y + z*z)";                          // south pole
Field[2] = MathEval; Field[2].F = Sprintf("sqrt(x*x + y*y + (z - %g)^2)", 2 * R);    // north pole
Field[3] = Threshold; Field[3].InField = 1; Field[3].SizeMin = h_master; Field[3].SizeMax = h_far;
Field[3].DistMin = d_fine; Field[3].DistMax = d_coarse;
Field[4] = Threshold; Field[4].InField = 2; Field[4].SizeMin = h_master; Field[4].SizeMax = h_far;
Field[4].DistMin = d_fine; Field[4].DistMax = d_coarse;
Field[5] = Threshold; Field[5].InField = 1; Field[5].SizeMin = h_slave; Field[5].SizeMax = h_far;
Field[5].DistMin = d_fine; Field[5].DistMax = d_coarse;
Field[6] = Restrict; Field[6].InField = 5; Field[6].VolumesList = {ball()};
Field[6].SurfacesList = {b_all()}; Field[6].CurvesList = {Abs(Boundary{ Surface{b_all()}; })};
Field[7] = Threshold; Field[7].InField = 2; Field[7].SizeMin = h_slave; Field[7].SizeMax = h_far;
Field[7].DistMin = d_fine; Field[7].DistMax = d_coarse;
up_all() = Abs(Boundary{ Volume{11}; });
Field[8] = Restrict; Field[8].InField = 7; Field[8].VolumesList = {11};
Field[8].SurfacesList = {up_all()}; Field[8].CurvesList = {Abs(Boundary{ Surface{up_all()}; })};
Field[9] = Min; Field[9].FieldsList = {3, 4, 6, 8};
Background Field = 9;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
