// Two identical elastic spheres pressed together (Hertz), as quarter models (x >= 0, y >= 0).
// Drawn in millimetres: read it with [mesh] unit = "mm".
//   "upper": the lower half of the sphere centred at (0, 0, +R), its pole at the origin pointing
//            down, its flat face on z = +R;
//   "lower": the upper half of the sphere centred at (0, 0, -R), its pole at the origin pointing
//            up, its flat face on z = -R.
// The two poles touch at the origin. The volumes are two separate OpenCASCADE solids that are
// never fragmented together: they share no point, curve or surface, so Gmsh meshes them as two
// bodies without common nodes, and the two curved surfaces get their own, non-matching meshes
// (different element sizes near the poles).
SetFactory("OpenCASCADE");
R = 50;          // radius of both spheres [mm]
h_up = 0.5;      // element size at the upper pole [mm]
h_low = 0.7;     // element size at the lower pole [mm]
h_far = 9;       // element size far from the contact [mm]
d_fine = 16;     // the fine size holds up to this distance from the origin [mm]
d_coarse = 50;   // and grows linearly to h_far at this distance [mm]
e = 1e-3;        // tolerance of the bounding-box searches [mm]

// Sphere(tag) = {xc, yc, zc, radius, latitude from, latitude to, azimuth range}
Sphere(1) = {0, 0,  R, R, -Pi/2, 0, Pi/2};   // upper: southern half, one quarter in azimuth
Sphere(2) = {0, 0, -R, R, 0, Pi/2, Pi/2};    // lower: northern half, one quarter in azimuth

Physical Volume("upper") = {1};
Physical Volume("lower") = {2};

// Upper body's faces.
up_top() = Surface In BoundingBox{-e, -e, R - e, R + e, R + e, R + e};
up_sx()  = Surface In BoundingBox{-e, -e, -e, e, R + e, R + e};      // the plane x = 0
up_sy()  = Surface In BoundingBox{-e, -e, -e, R + e, e, R + e};      // the plane y = 0
up_c()   = Abs(Boundary{ Volume{1}; });
up_c()  -= up_top();
up_c()  -= up_sx();
up_c()  -= up_sy();
// Lower body's faces.
lo_bot() = Surface In BoundingBox{-e, -e, -R - e, R + e, R + e, -R + e};
lo_sx()  = Surface In BoundingBox{-e, -e, -R - e, e, R + e, e};
lo_sy()  = Surface In BoundingBox{-e, -e, -R - e, R + e, e, e};
lo_c()   = Abs(Boundary{ Volume{2}; });
lo_c()  -= lo_bot();
lo_c()  -= lo_sx();
lo_c()  -= lo_sy();

Physical Surface("upper_contact") = {up_c()};
Physical Surface("lower_contact") = {lo_c()};
Physical Surface("upper_top") = {up_top()};
Physical Surface("lower_bottom") = {lo_bot()};
Physical Surface("upper_sym_x") = {up_sx()};
Physical Surface("upper_sym_y") = {up_sy()};
Physical Surface("lower_sym_x") = {lo_sx()};
Physical Surface("lower_sym_y") = {lo_sy()};

// Sizes: h_low (or h_up inside the upper body) within d_fine of the touching poles, growing to
// h_far at d_coarse. Field 3 is the lower size everywhere; field 5 is the finer size restricted to
// the upper body and its boundary; the mesh takes the smaller of the two.
Field[1] = MathEval; Field[1].F = "sqrt(x*x + y*y + z*z)";
Field[2] = Threshold; Field[2].InField = 1; Field[2].SizeMin = h_low; Field[2].SizeMax = h_far;
Field[2].DistMin = d_fine; Field[2].DistMax = d_coarse;
Field[3] = Threshold; Field[3].InField = 1; Field[3].SizeMin = h_up; Field[3].SizeMax = h_far;
Field[3].DistMin = d_fine; Field[3].DistMax = d_coarse;
up_curves() = Abs(Boundary{ Surface{ Abs(Boundary{ Volume{1}; }) }; });
Field[4] = Restrict; Field[4].InField = 3; Field[4].VolumesList = {1};
Field[4].SurfacesList = {Abs(Boundary{ Volume{1}; })}; Field[4].CurvesList = {up_curves()};
Field[5] = Min; Field[5].FieldsList = {2, 4};
Background Field = 5;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
