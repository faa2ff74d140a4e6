// A wheel segment of two materials on a rigid plane: a steel tyre (the ring r_hub < r < R) shrunk
// onto an aluminium hub with a bore; the axis is y, the wheel touches the plane z = 0 at the
// bottom of its tread. Only the tread near the bottom reaches the plane; the rest of the contact
// surface stays separated.
//   fricon mesh info examples/geometry/wheel.geo
SetFactory("OpenCASCADE");
R = 0.30;       // outer radius [m]
r_hub = 0.18;   // hub radius [m]
r_bore = 0.04;  // bore radius [m]
w = 0.10;       // width [m]
h_far = 0.03;   // element size away from the contact [m]
h_near = 0.006; // element size near the bottom of the tread [m]
Cylinder(1) = {0, -w/2, R, 0, w, 0, R};
Cylinder(2) = {0, -w/2, R, 0, w, 0, r_hub};
Cylinder(3) = {0, -w/2, R, 0, w, 0, r_bore};
BooleanDifference(4) = { Volume{2}; Delete; }{ Volume{3}; Delete; };
BooleanFragments{ Volume{1}; Delete; }{ Volume{4}; Delete; }
// After the fragments: the hub is the volume inside r_hub, the tyre the ring around it.
hub() = Volume In BoundingBox{-r_hub - 1e-6, -w, R - r_hub - 1e-6, r_hub + 1e-6, w, R + r_hub + 1e-6};
all() = Volume{:};
tyre() = all();
tyre() -= hub();
Physical Volume("hub") = {hub()};
Physical Volume("tyre") = {tyre()};
// The tread: the outer cylindrical surface; the bore: the inner one.
tread() = Surface In BoundingBox{-R - 1e-6, -w/2 - 1e-6, -1e-6, R + 1e-6, w/2 + 1e-6, 2*R + 1e-6};
sides() = Surface In BoundingBox{-R - 1e-6, -w/2 - 1e-6, -1e-6, R + 1e-6, -w/2 + 1e-6, 2*R + 1e-6};
sides() += Surface In BoundingBox{-R - 1e-6, w/2 - 1e-6, -1e-6, R + 1e-6, w/2 + 1e-6, 2*R + 1e-6};
inner() = Surface In BoundingBox{-r_hub - 1e-6, -w/2 - 1e-6, R - r_hub - 1e-6, r_hub + 1e-6, w/2 + 1e-6, R + r_hub + 1e-6};
tread() -= sides();
tread() -= inner();
bore() = Surface In BoundingBox{-r_bore - 1e-6, -w/2 - 1e-6, R - r_bore - 1e-6, r_bore + 1e-6, w/2 + 1e-6, R + r_bore + 1e-6};
bore() -= sides();
Physical Surface("tread") = {tread()};
Physical Surface("bore") = {bore()};
// Fine elements where the tread meets the plane.
Field[1] = Box;
Field[1].VIn = h_near; Field[1].VOut = h_far;
Field[1].XMin = -0.06; Field[1].XMax = 0.06; Field[1].YMin = -w; Field[1].YMax = w;
Field[1].ZMin = -0.01; Field[1].ZMax = 0.03; Field[1].Thickness = 0.05;
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
