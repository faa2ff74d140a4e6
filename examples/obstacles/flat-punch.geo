// A flat-ended rigid cylindrical punch of radius a on an elastic block (Boussinesq), as a quarter
// model (x >= 0, y >= 0). Drawn in millimetres: read it with [mesh] unit = "mm".
//   "block": the quarter of a 200 x 200 x 100 mm block, x and y in [0, L], z in [-H, 0], the only
//            physical volume (the only elastic body);
//   "punch": the surface of the cylinder r <= a, 0 <= z <= Hp, drawn whole (not a quarter:
//            faces on the symmetry planes would be nearer to the block's nodes there than its
//            flat end): its flat end on the block's top at z = 0, its side and its top, a closed
//            surface. The cylinder's volume is deleted (its surfaces stay), so nothing is meshed
//            inside it and no elastic body carries the surface: flat-punch.toml makes it a rigid
//            obstacle ([contact] obstacle kind "surface"), moved down into the block.
// The two solids are never fragmented together: the punch's end and the block's top lie in the
// same plane but are two surfaces with their own meshes. The block's elements are finest along
// the punch's rim, the circle r = a on the top, where the pressure is singular.
SetFactory("OpenCASCADE");
a = 1;           // radius of the punch [mm]
Hp = 1;          // height of the punch's piece that is drawn [mm]
L = 100;         // the quarter's extent in x and y [mm]
H = 100;         // depth of the block [mm]
h_rim = 0.025;   // element size at the rim (a / 40), up to d_fine from it [mm]
d_fine = 0.05;   // [mm]
growth = 0.12;   // beyond d_fine the size grows by this times the distance ...
h_far = 20;      // ... up to this size [mm]
e = 1e-4;        // tolerance of the bounding-box searches [mm]

Box(1) = {0, 0, -H, L, L, H};
Cylinder(2) = {0, 0, 0, 0, 0, Hp, a};   // the whole punch
Physical Volume("block") = {1};
punch() = Abs(Boundary{ Volume{2}; });
Delete { Volume{2}; }   // its surfaces stay: a closed shell with no volume, no mesh inside
top() = Surface In BoundingBox{-e, -e, -e, L + e, L + e, e};
top() -= punch();       // the punch's end lies in the plane z = 0 too
Physical Surface("top") = {top()};
Physical Surface("bottom") = {Surface In BoundingBox{-e, -e, -H - e, L + e, L + e, -H + e}};
Physical Surface("sym_x") = {Surface In BoundingBox{-e, -e, -H - e, e, L + e, e}};   // x = 0
Physical Surface("sym_y") = {Surface In BoundingBox{-e, -e, -H - e, L + e, e, e}};   // y = 0
Physical Surface("punch") = {punch()};

// Sizes by the distance from the rim (the circle r = a, z = 0 of the punch's end).
rim() = Curve In BoundingBox{-a - e, -a - e, -e, a + e, a + e, e};
Field[1] = Distance; Field[1].CurvesList = {rim()}; Field[1].NumPointsPerCurve = 400;
Field[2] = Threshold; Field[2].InField = 1;
Field[2].SizeMin = h_rim; Field[2].SizeMax = h_far;
Field[2].DistMin = d_fine; Field[2].DistMax = d_fine + (h_far - h_rim) / growth;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
