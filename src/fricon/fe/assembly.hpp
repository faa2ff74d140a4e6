#pragma once
// fe: assembly of the stiffness matrix K and the load vector f over the free dofs (theory.md §2.1,
// §2.12), for the mesh's element (fe/element.hpp). On straight-sided cells all integrals are
// exact for the data they accept (constant tractions and volume forces, or fields interpolated
// by the element's shape functions); on curved cells they are the element's quadrature.

#include <span>

#include <vector>

#include "fricon/core/types.hpp"
#include "fricon/fe/dof_map.hpp"
#include "fricon/fe/material.hpp"
#include "fricon/mesh/tet_mesh.hpp"

namespace fricon::fe {

using NodalField = Eigen::Matrix<Real, 3, Eigen::Dynamic>;

/// Stiffness matrix K [N/m] over the free dofs of `dofs`: symmetric, both triangles stored, with
/// the sparsity of the node graph (every pair of nodes of one element). Positive definite
/// when the Dirichlet conditions remove the rigid motions.
SparseMatrix assemble_stiffness(const mesh::TetMesh& mesh, Materials materials, const DofMap& dofs);
/// One material everywhere.
inline SparseMatrix assemble_stiffness(const mesh::TetMesh& mesh, const Material& material,
                                       const DofMap& dofs) {
  return assemble_stiffness(mesh, Materials(&material, 1), dofs);
}

/// Adds the load of a constant surface traction p [Pa] on the boundary triangles `faces` to f [N]:
/// node a of triangle T receives int_T phi_a dS p (|T|/3 at each corner of a 3-node triangle;
/// 0 at the corners and |T|/3 at the edge nodes of a straight 6-node one).
void add_traction(const mesh::TetMesh& mesh, const DofMap& dofs, const std::vector<Index>& faces,
                  const Vec3& p, VectorXd& f);

/// Adds the load of a surface traction with nodal values p (3 x n_nodes) [Pa] on `faces`,
/// interpolated by the face element: node a receives sum_b int_T phi_a phi_b dS p_b.
void add_traction_field(const mesh::TetMesh& mesh, const DofMap& dofs,
                        const std::vector<Index>& faces, const NodalField& p, VectorXd& f);

/// Adds the load of a constant volume force b [N/m^3]: node a receives int_T phi_a dV b (|T|/4
/// at each corner of a 4-node tetrahedron).
void add_volume_force(const mesh::TetMesh& mesh, const DofMap& dofs, const Vec3& b, VectorXd& f);

/// Adds the load of a volume force with nodal values b (3 x n_nodes) [N/m^3], interpolated by
/// the element: node a receives sum_b int_T phi_a phi_b dV b_b.
void add_volume_force_field(const mesh::TetMesh& mesh, const DofMap& dofs, const NodalField& b,
                            VectorXd& f);

/// Nodal forces [N] of the stiffness on all 3 n_nodes components (fixed ones included): the
/// internal force K_full u for a displacement field given at the nodes. Used for reactions.
NodalField internal_forces(const mesh::TetMesh& mesh, Materials materials, const NodalField& u);

/// internal_forces summed over the tetrahedra `tets` only: exact at the nodes all of whose
/// tetrahedra are listed (e.g. the nodes with a fixed dof, for their reactions).
NodalField internal_forces(const mesh::TetMesh& mesh, Materials materials, const NodalField& u,
                           std::span<const Index> tets);

/// The node graph of the mesh in CSR arrays: node a's neighbours (the nodes of the elements
/// it belongs to, a itself included) are adj[start[a] .. start[a+1]), ascending.
struct NodeGraph {
  std::vector<SparseIndex> start;  ///< size n_nodes + 1
  std::vector<SparseIndex> adj;
};
NodeGraph node_graph(const mesh::TetMesh& mesh);

}  // namespace fricon::fe
