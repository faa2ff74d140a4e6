// A slab in plane strain under a rigid cylinder whose axis is along y (Hertz's line contact), as
// a half model (x >= 0): the slab's section x in [0, L], z in [-H, 0] (the plane y = 0), meshed in
// 2D and extruded along y by one layer of thickness t. Every node then lies on one of the faces
// y = 0 and y = t, which cylinder-slab.toml holds in y: the displacement is the plane-strain one,
// uniform in y. The cylinder is no mesh: cylinder-slab.toml gives it as [contact] obstacle kind
// "cylinder", touching the top z = 0 along the y axis. Drawn in millimetres: read it with
// [mesh] unit = "mm".
//
// The sizes are set for cylinder-slab.toml's contact half-width b = 0.1 mm: h_c = b / 25 up to
// 1.6 b from the axis, then growing by 7 % of the distance up to h_far. The slab is 250 b wide
// (twice that in the whole) and deep. t = h_c: the contact face is a strip of near-square
// triangle pairs. `--set mesh.size_factor=X` scales the in-plane sizes (not t).
L = 25;          // half width of the slab [mm]
H = 25;          // depth of the slab [mm]
t = 0.004;       // thickness along y [mm]
h_c = 0.004;     // element size at the contact, up to d_fine from the axis [mm]
d_fine = 0.16;   // [mm]
growth = 0.07;   // beyond d_fine the size grows by this times the distance ...
h_far = 4;       // ... up to this size [mm]

Point(1) = {0, 0, 0, h_c};
Point(2) = {L, 0, 0, h_far};
Point(3) = {L, 0, -H, h_far};
Point(4) = {0, 0, -H, h_far};
Line(1) = {1, 2};     // the top, z = 0
Line(2) = {2, 3};     // the side x = L
Line(3) = {3, 4};     // the bottom, z = -H
Line(4) = {4, 1};     // the symmetry plane x = 0
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

// The section's sizes by the distance from the point where the cylinder touches it.
Field[1] = Distance; Field[1].PointsList = {1};
Field[2] = Threshold; Field[2].InField = 1;
Field[2].SizeMin = h_c; Field[2].SizeMax = h_far;
Field[2].DistMin = d_fine; Field[2].DistMax = d_fine + (h_far - h_c) / growth;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;

// One layer of tetrahedra along y (no Recombine: each prism is cut into three tetrahedra).
slab[] = Extrude {0, t, 0} { Surface{1}; Layers{1}; };
// slab[0]: the face y = t, slab[1]: the volume, slab[2..5]: the faces swept by lines 1..4.
Physical Volume("slab") = {slab[1]};
Physical Surface("top") = {slab[2]};
Physical Surface("bottom") = {slab[4]};
Physical Surface("sym_x") = {slab[5]};
Physical Surface("y0") = {1};
Physical Surface("y1") = {slab[0]};
