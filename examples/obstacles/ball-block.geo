// A rigid ball on an elastic block (Hertz), as a quarter model (x >= 0, y >= 0): the quarter of a
// 50 x 50 x 25 mm block, x and y in [0, L], z in [-H, 0], its top face z = 0 touched at the
// origin by the ball. The ball is no mesh: ball-block.toml gives it as [contact] obstacle
// kind "sphere". Drawn in millimetres: read it with [mesh] unit = "mm".
//
// The sizes are set for ball-block.toml's contact radius a = 0.1 mm: h_c = a / 20 up to 1.6 a
// from the origin (the candidates of the contact search reach sqrt(2) a), then growing by a tenth
// of the distance up to h_far. The grading is gentle because much of the P1 elements' excess
// stiffness, which makes the force of a prescribed indentation too large, comes from the graded
// zone (halving the growth did more for the force than a finer contact zone). The block
// is 250 a wide and deep: its clamped bottom and free sides change the force of the indentation
// by a few tenths of a percent from the half-space's (a block twice as large lowers the force by
// 0.1 to 0.2 %). `--set mesh.size_factor=X` scales every size.
SetFactory("OpenCASCADE");
L = 25;          // the quarter's extent in x and y [mm]
H = 25;          // depth of the block [mm]
h_c = 0.005;     // element size at the contact, up to d_fine from the origin [mm]
d_fine = 0.16;   // [mm]
growth = 0.1;    // beyond d_fine the size grows by this times the distance ...
h_far = 5;       // ... up to this size [mm]
e = 1e-4;        // tolerance of the bounding-box searches [mm]

Box(1) = {0, 0, -H, L, L, H};
Physical Volume("block") = {1};
Physical Surface("top") = {Surface In BoundingBox{-e, -e, -e, L + e, L + e, e}};
Physical Surface("bottom") = {Surface In BoundingBox{-e, -e, -H - e, L + e, L + e, -H + e}};
Physical Surface("sym_x") = {Surface In BoundingBox{-e, -e, -H - e, e, L + e, e}};   // x = 0
Physical Surface("sym_y") = {Surface In BoundingBox{-e, -e, -H - e, L + e, e, e}};   // y = 0

// Sizes by the distance from the origin, where the ball touches the block.
origin() = Point In BoundingBox{-e, -e, -e, e, e, e};
Field[1] = Distance; Field[1].PointsList = {origin()};
Field[2] = Threshold; Field[2].InField = 1;
Field[2].SizeMin = h_c; Field[2].SizeMax = h_far;
Field[2].DistMin = d_fine; Field[2].DistMax = d_fine + (h_far - h_c) / growth;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
