// A plate 1 x 1 x 0.2 m with a physical curve "edge" (y = 0, z = 0) and a physical point
// "corner" (0, 0, 0) besides its faces: the bad-input cases 143-145 name them where a surface is
// needed.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 0.2};
e = 1e-6;
Physical Volume("plate") = {1};
Physical Surface("x0") = Surface In BoundingBox{-e, -e, -e, e, 1 + e, 0.2 + e};
Physical Surface("y1") = Surface In BoundingBox{-e, 1 - e, -e, 1 + e, 1 + e, 0.2 + e};
Physical Surface("z0") = Surface In BoundingBox{-e, -e, -e, 1 + e, 1 + e, e};
Physical Curve("edge") = Curve In BoundingBox{-e, -e, -e, 1 + e, e, e};
Physical Point("corner") = Point In BoundingBox{-e, -e, -e, e, e, e};
MeshSize{PointsOf{Volume{1};}} = 0.25;
