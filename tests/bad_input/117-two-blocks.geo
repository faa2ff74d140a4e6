// Two unit blocks stacked, separate volumes that share no node: "lower" (0 < z < 1) and "upper"
// (1 < z < 2), touching at z = 1 with non-matching meshes. The two-body bad-input cases
// (117-...-123-...) pair their faces wrongly. OpenCASCADE numbers a box's faces x = 0, x = 1,
// y = 0, y = 1, z = 0, z = 1.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Box(2) = {0, 0, 1, 1, 1, 1};
Physical Volume("lower") = {1};
Physical Volume("upper") = {2};
Physical Surface("lower_bottom") = {5};
Physical Surface("lower_top") = {6};
Physical Surface("upper_bottom") = {11};
Physical Surface("upper_top") = {12};
MeshSize{PointsOf{Volume{1};}} = 0.5;
MeshSize{PointsOf{Volume{2};}} = 0.35;
