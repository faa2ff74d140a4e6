// A rigid ball on an elastic block, as a half model (y >= 0; a slide along x keeps the plane
// y = 0 a plane of symmetry): the half of a 50 x 50 x 25 mm block, x in [-L, L], y in [0, L],
// z in [-H, 0], its top face z = 0 touched at the origin by the ball. The ball is no mesh:
// ball-slide.toml gives it as [contact] obstacle kind "sphere". Drawn in millimetres: read it
// with [mesh] unit = "mm".
//
// The sizes are set for ball-slide.toml's contact radius a = 0.1 mm: h_c = a / 30 up to 1.1 a
// from the origin, growing by 15 % of the distance beyond. The stick radius that
// check_obstacles.py measures (from the area of the patches that stick) is short by about one
// element size h_c (the patches the stick boundary crosses count as slipping), hence the fine
// contact mesh; the force of the indentation is not checked on this model, hence the faster
// grading than ball-block.geo's. `--set mesh.size_factor=X` scales every size.
SetFactory("OpenCASCADE");
L = 25;           // half width of the block, and its extent in y [mm]
H = 25;           // depth of the block [mm]
h_c = 0.00333;    // element size at the contact, up to d_fine from the origin [mm]
d_fine = 0.11;    // [mm]
growth = 0.15;    // beyond d_fine the size grows by this times the distance ...
h_far = 5;        // ... up to this size [mm]
e = 1e-4;         // tolerance of the bounding-box searches [mm]

Box(1) = {-L, 0, -H, 2 * L, L, H};
Physical Volume("block") = {1};
Physical Surface("top") = {Surface In BoundingBox{-L - e, -e, -e, L + e, L + e, e}};
Physical Surface("bottom") = {Surface In BoundingBox{-L - e, -e, -H - e, L + e, L + e, -H + e}};
Physical Surface("sym_y") = {Surface In BoundingBox{-L - e, -e, -H - e, L + e, e, e}};   // y = 0

// Sizes by the distance from the origin, where the ball touches the block (no point of the
// geometry lies there: the distance is a formula).
Field[1] = MathEval; Field[1].F = "sqrt(x*x + y*y + z*z)";
Field[2] = Threshold; Field[2].InField = 1;
Field[2].SizeMin = h_c; Field[2].SizeMax = h_far;
Field[2].DistMin = d_fine; Field[2].DistMax = d_fine + (h_far - h_c) / growth;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
