#pragma once
// feti: the partition of the bodies into subdomains, the first stage of the Total FETI backend
// ([solver] backend = "tfeti"). Each subdomain is a set of tetrahedra of one body that is
// face-connected (any two of its tetrahedra are joined by a chain of its tetrahedra, each sharing
// a triangular face with the next), so that its stiffness matrix has the rigid motions of one
// piece as kernel and nothing more. Subdomains are glued back together later by the Lagrange
// multipliers of TFETI; here they are only sets of tetrahedra.
//
// The graph partitioner is METIS (Debian: libmetis-dev), called on the dual graph of each body;
// a build without METIS can still give each body one subdomain, and says how to get METIS when
// more are asked for.

#include <string>
#include <vector>

#include "fricon/core/types.hpp"
#include "fricon/feti/feti_options.hpp"
#include "fricon/mesh/bodies.hpp"
#include "fricon/mesh/tet_mesh.hpp"

namespace fricon::feti {

/// Which subdomain each tetrahedron of a mesh belongs to. Subdomains are numbered body by body
/// (those of body 0 first), and within a body in the order of their first (smallest) tetrahedron.
/// Every subdomain is non-empty, face-connected and inside one body.
struct Partition {
  /// Per tetrahedron of the mesh (n_tets entries), its subdomain 0 .. n_subdomains - 1.
  std::vector<Index> subdomain_of_tet;
  /// The number of subdomains.
  Index n_subdomains = 0;
  /// Per subdomain, its tetrahedra in ascending order.
  std::vector<std::vector<Index>> tets;
  /// The number of parts (METIS's, or a whole body given one subdomain) that were not
  /// face-connected and were split into their face-connected pieces, each its own subdomain.
  Index n_split = 0;
  /// One sentence for the report when the partition differs from the request (fewer subdomains
  /// asked for than there are bodies, parts split, empty parts dropped), else empty.
  std::string note;
};

/// Throws InputError, with `key_context` (where solver.subdomains was given) and the numbers,
/// when `n_subdomains` is below 1 or above the tetrahedra of `mesh` (each subdomain needs one).
void check_subdomain_count(const mesh::TetMesh& mesh, Index n_subdomains,
                           const std::string& key_context);

/// The number of subdomains for a target `subdomain_size` (nodes per subdomain, >= 1) on `mesh`:
/// mesh.n_nodes() / subdomain_size rounded to the nearest integer, at least 1 and at most
/// mesh.n_tets() (when the mesh has tetrahedra), so that partition_mesh accepts it. Nodes on the
/// interface of two subdomains count in both, so the subdomains come out slightly larger than
/// the target. All nodes count (the edge nodes of a quadratic mesh too).
Index subdomains_for_size(const mesh::TetMesh& mesh, Index subdomain_size);

/// Partition of every body of `mesh` (`bodies` = mesh::find_bodies(mesh)) into about
/// `n_subdomains` subdomains in total. The subdomains are distributed over the bodies in
/// proportion to their tetrahedra, each body at least 1: one by one, each goes to the body whose
/// subdomains are the largest (most tetrahedra per subdomain). Each body given k > 1 subdomains
/// is partitioned by METIS_PartGraphKway on its dual graph (tetrahedra adjacent when they share a
/// triangular face, read from the corner nodes mesh.tets), with a fixed seed so that the result
/// is deterministic, and contiguous parts asked for. A body given 1 subdomain is one, without
/// METIS (so n_subdomains == bodies.n_bodies(), or 1, needs no METIS). A part that is not
/// face-connected is split into its face-connected pieces, and a part that METIS leaves empty is
/// dropped, so the result may have a few more or fewer subdomains than asked (said in `note`).
/// When n_subdomains < bodies.n_bodies(), each body is one subdomain (said in `note`).
/// Throws InputError naming `key_context` (where solver.subdomains was given, e.g. the position
/// in the problem file) and the key solver.subdomains when n_subdomains < 1, when n_subdomains
/// exceeds the tetrahedra of the mesh, or when a body needs METIS and this fricon was built
/// without it.
Partition partition_mesh(const mesh::TetMesh& mesh, const mesh::Bodies& bodies, Index n_subdomains,
                         const std::string& key_context);

/// `partition` with each subdomain of `necked` (joined by a neck: feti/softness.hpp) cut again
/// together with the subdomains that share a face with it: the union of them (regions that share
/// a subdomain merged) is partitioned by METIS into as many parts as it had, contiguous, seeded
/// for round `round` (>= 1; partition_mesh's partition is round 0), a part that is not
/// face-connected split into its pieces (counted in n_split). The other subdomains keep their
/// tetrahedra; all are numbered as partition_mesh numbers them, and `note` is kept. A necked
/// subdomain alone in its body is kept. theory.md §8.9. Throws as partition_mesh does, naming
/// `key_context`.
Partition recut_necked(const mesh::TetMesh& mesh, const mesh::Bodies& bodies,
                       const Partition& partition, const std::vector<Index>& necked, Index round,
                       const std::string& key_context);

}  // namespace fricon::feti
