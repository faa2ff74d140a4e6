// A block on a block on a rigid floor, as quarter models (x >= 0, y >= 0; the full blocks are
// centred on the z axis). Drawn in millimetres: read it with [mesh] unit = "mm".
//   "lower": the quarter of a 30 x 30 x 10 block: x and y in [0, 15], z in [0, 10]; it rests on
//            the rigid plane z = 0 (no geometry: the problem file's plane obstacle);
//   "upper": the quarter of a 20 x 20 x 10 block: x and y in [0, 10], z in [10, 20].
// The blocks touch on the plane z = 10; they are separate OpenCASCADE solids (no common node).
// The lower block is cut at z = z_clamp into two volumes of the same region, only so that its
// outer side faces x = 15 and y = 15 get a strip z in [0, z_clamp] of their own: "lower_clamp",
// where the problem file holds the block vertically (see stacked-blocks.toml).
SetFactory("OpenCASCADE");
h_up = 1.2;     // element size in the upper block [mm]
h_low = 1.6;    // element size in the lower block [mm]
z_clamp = 2;    // height of the clamped strip at the foot of the lower block [mm]
e = 1e-3;       // tolerance of the bounding-box searches [mm]

Box(1) = {0, 0, 10, 10, 10, 10};            // upper
Box(2) = {0, 0, 0, 15, 15, 10};             // lower
Box(3) = {0, 0, 0, 15, 15, z_clamp};        // the foot of the lower block, to cut it
// Only the lower block is fragmented (with its own foot); the upper block is left out.
lower() = BooleanFragments{ Volume{2}; Delete; }{ Volume{3}; Delete; };
Physical Volume("upper") = {1};
Physical Volume("lower") = {lower()};

Physical Surface("upper_top") = Surface In BoundingBox{-e, -e, 20 - e, 10 + e, 10 + e, 20 + e};
Physical Surface("upper_bottom") = Surface In BoundingBox{-e, -e, 10 - e, 10 + e, 10 + e, 10 + e};
lo_top() = Surface In BoundingBox{-e, -e, 10 - e, 15 + e, 15 + e, 10 + e};
lo_top() -= Surface In BoundingBox{-e, -e, 10 - e, 10 + e, 10 + e, 10 + e};
Physical Surface("lower_top") = {lo_top()};
Physical Surface("lower_bottom") = Surface In BoundingBox{-e, -e, -e, 15 + e, 15 + e, e};
Physical Surface("upper_sym_x") = Surface In BoundingBox{-e, -e, 10 - e, e, 10 + e, 20 + e};
Physical Surface("upper_sym_y") = Surface In BoundingBox{-e, -e, 10 - e, 10 + e, e, 20 + e};
Physical Surface("lower_sym_x") = Surface In BoundingBox{-e, -e, -e, e, 15 + e, 10 + e};
Physical Surface("lower_sym_y") = Surface In BoundingBox{-e, -e, -e, 15 + e, e, 10 + e};
clamp() = Surface In BoundingBox{15 - e, -e, -e, 15 + e, 15 + e, z_clamp + e};
clamp() += Surface In BoundingBox{-e, 15 - e, -e, 15 + e, 15 + e, z_clamp + e};
Physical Surface("lower_clamp") = {clamp()};

MeshSize{ PointsOf{ Volume{1}; } } = h_up;
MeshSize{ PointsOf{ Volume{lower()}; } } = h_low;
Mesh.MeshSizeExtendFromBoundary = 1;
Mesh.MeshSizeFromCurvature = 0;
