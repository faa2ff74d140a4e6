#pragma once
// contact: how far the master surface of a pair penetrates the slave after a solve (theory.md
// §2.8). The constraints are the slave's: each slave patch may not enter the master in the mean.
// Nothing keeps the master's nodes out of the slave, so a master much finer than the slave can
// sink its nodes between the slave's, where no multiplier sees them; this measures it.
//
// Each master node a looks along its area-weighted mean outward normal m_a, within the search
// distance, for the slave triangle facing it (the reference pairing of the master's side); with t
// the initial gap along that ray and u the displacement, the deformed gap is
// t + (u_s(hit) - u_a) . m_a, and the master node penetrates the slave by its negative part.

#include <string>

#include "fricon/contact/contact_surface.hpp"
#include "fricon/core/types.hpp"
#include "fricon/mesh/tet_mesh.hpp"

namespace fricon::contact {

struct MasterPenetration {
  Real depth = 0.0;  ///< the largest penetration of a master node into the slave [m] (>= 0)
  Index node = -1;   ///< that master node (a mesh node), -1 when none penetrates
  /// The largest |u . normal| [m] over the slave's nodes of the pair and the master nodes that
  /// found the slave: how far the two surfaces moved along their normals, the scale the depth
  /// is compared with.
  Real normal_displacement = 0.0;
};

/// The penetration of master tag `master` into the slave triangles of pair `pair` of `surface`
/// (those whose nodes have node_pair == pair), for the displacement `u` (3 x mesh nodes [m], the
/// prescribed values included), with rays of length `search_distance` [m] > 0. Master nodes
/// whose ray finds no slave triangle facing them are out of reach and count for nothing.
MasterPenetration master_penetration(const mesh::TetMesh& mesh, const ContactSurface& surface,
                                     Index pair, const std::string& master, Real search_distance,
                                     const Eigen::Matrix<Real, 3, Eigen::Dynamic>& u);

}  // namespace fricon::contact
