// Two disjoint blocks that share no node: "held" (0 < x < 1) and "loose" (2 < x < 3), each with
// its base tagged ("base", "loose_base"). 115-two-bodies-one-free.toml clamps only "base";
// tests/verification/two_bodies_test.cpp clamps both and solves.
SetFactory("OpenCASCADE");
a = 1.0;    // edge of each block [m]
gap = 1.0;  // distance between the blocks [m]
h = 0.5;    // element size [m]
Box(1) = {0, 0, 0, a, a, a};
Box(2) = {a + gap, 0, 0, a, a, a};
Physical Volume("held") = {1};
Physical Volume("loose") = {2};
Physical Surface("base") = {Surface In BoundingBox{-1e-6, -1e-6, -1e-6, a + 1e-6, a + 1e-6, 1e-6}};
Physical Surface("loose_base") = {Surface In BoundingBox{a + gap - 1e-6, -1e-6, -1e-6,
                                                         2*a + gap + 1e-6, a + 1e-6, 1e-6}};
Physical Surface("loose_top") = {Surface In BoundingBox{a + gap - 1e-6, -1e-6, a - 1e-6,
                                                        2*a + gap + 1e-6, a + 1e-6, a + 1e-6}};
Mesh.MeshSizeMin = h;
Mesh.MeshSizeMax = h;
