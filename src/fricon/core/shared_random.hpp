#pragma once
// core: the C library's random sequence (rand/srand), which is one for the whole process. Gmsh's
// mesher and METIS (the bisection of CHOLMOD's nested dissection) both seed it and draw from it.
// When one ran while the other did, in another thread, each drew numbers the other had seeded:
// a .geo meshed next to another solve could get another mesh (234 or 263 nodes for the same
// file) and an ordering another fill. Both are therefore called with this lock held
// (mesh/gmsh_file.cpp, linalg/cholesky.cpp), so that a run gives the answer it gives alone,
// whatever else the process runs (docs/python.md, "Threads").

#include <mutex>

namespace fricon {

/// The lock of the C library's random sequence: hold it around any call into a library that
/// seeds or draws from rand() (Gmsh, METIS). A Gmsh session takes it after Gmsh's own lock; no
/// lock is taken while it is held.
std::mutex& shared_random_mutex();

}  // namespace fricon
