// 115-two-bodies-one-free.geo with two more tags on the held block: its back face x = 0
// ("held_back") and, for the contact, its bottom ("base"). 148-floating-no-contact-surface.toml
// clamps "held_back", puts "base" on the rigid plane z = 0 and leaves "loose" (2 < x < 3) to
// nothing: a floating body that no contact surface touches.
SetFactory("OpenCASCADE");
a = 1.0;    // edge of each block [m]
gap = 1.0;  // distance between the blocks [m]
h = 0.5;    // element size [m]
Box(1) = {0, 0, 0, a, a, a};
Box(2) = {a + gap, 0, 0, a, a, a};
Physical Volume("held") = {1};
Physical Volume("loose") = {2};
Physical Surface("base") = {Surface In BoundingBox{-1e-6, -1e-6, -1e-6, a + 1e-6, a + 1e-6, 1e-6}};
Physical Surface("held_back") = {Surface In BoundingBox{-1e-6, -1e-6, -1e-6, 1e-6, a + 1e-6,
                                                        a + 1e-6}};
Physical Surface("loose_base") = {Surface In BoundingBox{a + gap - 1e-6, -1e-6, -1e-6,
                                                         2*a + gap + 1e-6, a + 1e-6, 1e-6}};
Physical Surface("loose_top") = {Surface In BoundingBox{a + gap - 1e-6, -1e-6, a - 1e-6,
                                                        2*a + gap + 1e-6, a + 1e-6, a + 1e-6}};
Mesh.MeshSizeMin = h;
Mesh.MeshSizeMax = h;
