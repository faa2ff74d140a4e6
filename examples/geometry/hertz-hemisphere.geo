// A hemisphere of radius R on a rigid plane (Hertz): the curved surface "contact" touches the
// plane z = 0 at the pole, the flat face "top" (z = R) is pressed down by a prescribed displacement.
SetFactory("OpenCASCADE");
R = 0.05;        // radius [m]
h_tip = 0.0003;  // element size at the pole [m]
h_far = 0.015;   // element size far from it [m]
Sphere(1) = {0, 0, R, R, -Pi/2, 0, 2*Pi};
Physical Volume("ball") = {1};
flat() = Surface In BoundingBox{-2*R, -2*R, R - 1e-6, 2*R, 2*R, R + 1e-6};
curved() = Abs(Boundary{Volume{1};});
curved() -= flat();
Physical Surface("contact") = {curved()};
Physical Surface("top") = {flat()};
pole() = Point In BoundingBox{-1e-6, -1e-6, -1e-6, 1e-6, 1e-6, 1e-6};
Field[1] = Distance; Field[1].PointsList = {pole()};
Field[2] = Threshold; Field[2].InField = 1;
Field[2].SizeMin = h_tip; Field[2].SizeMax = h_far; Field[2].DistMin = 0.005; Field[2].DistMax = 0.03;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
