// A small block pressed and sheared on a larger one. Drawn in millimetres: read it with
// [mesh] unit = "mm".
//   "upper": 20 x 20 x 10, x and y in [-10, 10], z in [0, 10];
//   "lower": 40 x 40 x 10, x and y in [-20, 20], z in [-10, 0].
// The blocks touch on the plane z = 0. They are two separate OpenCASCADE boxes, never fragmented
// together: no common point, curve or surface, hence no common node. The upper block's bottom lies
// inside the lower block's top face, and the two are meshed with different element sizes, so
// their triangles do not match.
SetFactory("OpenCASCADE");
h_up = 2.5;    // element size in the upper block [mm]
h_low = 3.3;   // element size in the lower block [mm]
e = 1e-3;      // tolerance of the bounding-box searches [mm]

Box(1) = {-10, -10, 0, 20, 20, 10};
Box(2) = {-20, -20, -10, 40, 40, 10};
Physical Volume("upper") = {1};
Physical Volume("lower") = {2};

up_bot() = Surface In BoundingBox{-10 - e, -10 - e, -e, 10 + e, 10 + e, e};
up_top() = Surface In BoundingBox{-10 - e, -10 - e, 10 - e, 10 + e, 10 + e, 10 + e};
lo_top() = Surface In BoundingBox{-20 - e, -20 - e, -e, 20 + e, 20 + e, e};
lo_top() -= up_bot();
lo_bot() = Surface In BoundingBox{-20 - e, -20 - e, -10 - e, 20 + e, 20 + e, -10 + e};
Physical Surface("upper_bottom") = {up_bot()};   // the slave surface
Physical Surface("lower_top") = {lo_top()};      // the master surface, the whole top face
Physical Surface("upper_top") = {up_top()};
Physical Surface("lower_bottom") = {lo_bot()};

// One size per block, given at its corners (the blocks have no point in common).
MeshSize{ PointsOf{ Volume{1}; } } = h_up;
MeshSize{ PointsOf{ Volume{2}; } } = h_low;
Mesh.MeshSizeExtendFromBoundary = 1;
Mesh.MeshSizeFromCurvature = 0;
