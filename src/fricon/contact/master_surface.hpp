#pragma once
// contact: a contact surface against another surface of the mesh, the master, usually of another
// elastic body (theory.md §2.8). Small sliding: the pairing of slave and master is computed once,
// in the reference configuration.
//
//   1. each node of the slave tag looks for the master along its mean outward normal, within the
//      search distance d (SurfaceLocator::ray_hit); the hit gives the node's gap (the distance
//      along the normal) and the master's displacement at the projection (the face element's
//      shape functions of the master triangle at the hit on its flat corner triangle: theory.md
//      §2.12);
//   2. the contact surface is the slave triangles all of whose nodes found a master triangle
//      facing them: the rest is out of reach and carries no multipliers;
//   3. once the patches are built, mortar_matrix integrates the master's shape functions over
//      each patch, on the intersections of the slave triangles with the master triangles
//      projected along the patch normal (mortar_geometry.hpp): the master's columns of B.

#include <memory>
#include <string>
#include <vector>

#include "fricon/contact/contact_surface.hpp"
#include "fricon/contact/mortar_geometry.hpp"
#include "fricon/contact/patches.hpp"
#include "fricon/core/types.hpp"
#include "fricon/fe/dof_map.hpp"
#include "fricon/mesh/tet_mesh.hpp"

namespace fricon::contact {

/// What a pair against a body needs to know: the master's tag, the search distance and where
/// the keys were given, for messages.
struct MasterSpec {
  std::string boundary;        ///< tag of the master surface
  Real search_distance = 0.0;  ///< d [m]; 0: a tenth of the slave tag's diameter
  /// Body of each mesh node (mesh::Bodies::node_body), to refuse a slave and a master on one
  /// body (self-contact); empty: not checked.
  std::vector<Index> node_body;
  /// Where the master's tag was given and its key ("file:20:1: contact[0].obstacle.boundary").
  std::string where_boundary = "contact.obstacle.boundary";
};

/// The contact surface of tag `slave` against the master, with each node's gap and the master's
/// interpolation (ContactSurface::master, master_prescribed from `prescribed`, 3 x mesh nodes or
/// empty).
struct SlaveSurface {
  ContactSurface surface;
  VectorXd gap;                  ///< per surface node, along its normal [m]
  Real search_distance = 0.0;    ///< d as used [m]
  Index n_tag_faces = 0;         ///< triangles of the slave tag (the surface keeps those in reach)
  Real master_element_size = 0;  ///< mean edge length of the master triangles [m]
  /// The master's triangles, located (built once: the rays and the mortar integrals use it).
  std::shared_ptr<const SurfaceLocator> master;
};

/// Steps 1 and 2 above. Throws InputError naming `where` (the slave's contact.boundary) or
/// master.where_boundary: a tag that does not exist, a slave and a master on one body, surfaces
/// whose normals do not face each other, no slave node within the search distance of the
/// master, a node that starts inside the master.
SlaveSurface make_slave_surface(const mesh::TetMesh& mesh, const fe::DofMap& dofs,
                                const std::string& slave, const std::string& where,
                                const MasterSpec& master,
                                const Eigen::Matrix<Real, 3, Eigen::Dynamic>& prescribed);

/// Step 3: mortar(p, a) = int_{R_p} (shape function of master node a at the projection along the
/// patch normal) dS [m^2], n_patches x mesh nodes; `coverage` receives sum(mortar) / |surface|,
/// the share of the contact surface that the master covers (1 up to rounding when every slave
/// triangle lies opposite the master).
SparseMatrix mortar_matrix(const mesh::TetMesh& mesh, const ContactSurface& surface,
                           const Patches& patches, const Frames& frames,
                           const SurfaceLocator& master, Real search_distance, Real& coverage);

}  // namespace fricon::contact
