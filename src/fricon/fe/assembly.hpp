#pragma once
// fe: assembly of the stiffness matrix K and the load vector f over the free dofs (theory.md §2.1).
// All integrals are exact for the data they accept (constant or P1 tractions and volume forces).

#include <span>

#include <vector>

#include "fricon/core/types.hpp"
#include "fricon/fe/dof_map.hpp"
#include "fricon/fe/material.hpp"
#include "fricon/mesh/tet_mesh.hpp"

namespace fricon::fe {

using NodalField = Eigen::Matrix<Real, 3, Eigen::Dynamic>;

/// Stiffness matrix K [N/m] over the free dofs of `dofs`: symmetric, both triangles stored, with
/// the sparsity of the node graph (every pair of nodes sharing a tetrahedron). Positive definite
/// when the Dirichlet conditions remove the rigid motions.
SparseMatrix assemble_stiffness(const mesh::TetMesh& mesh, Materials materials, const DofMap& dofs);
/// One material everywhere.
inline SparseMatrix assemble_stiffness(const mesh::TetMesh& mesh, const Material& material,
                                       const DofMap& dofs) {
  return assemble_stiffness(mesh, Materials(&material, 1), dofs);
}

/// Adds the load of a constant surface traction p [Pa] on the boundary triangles `faces` to f [N]:
/// each vertex of triangle T receives |T|/3 p (exact for P1 test functions).
void add_traction(const mesh::TetMesh& mesh, const DofMap& dofs, const std::vector<Index>& faces,
                  const Vec3& p, VectorXd& f);

/// Adds the load of a P1 surface traction with nodal values p (3 x n_nodes) [Pa] on `faces`,
/// integrated exactly with the triangle mass matrix |T|/12 (1 + delta_ab).
void add_traction_p1(const mesh::TetMesh& mesh, const DofMap& dofs, const std::vector<Index>& faces,
                     const NodalField& p, VectorXd& f);

/// Adds the load of a constant volume force b [N/m^3]: each vertex receives |T|/4 b.
void add_volume_force(const mesh::TetMesh& mesh, const DofMap& dofs, const Vec3& b, VectorXd& f);

/// Adds the load of a P1 volume force with nodal values b (3 x n_nodes) [N/m^3], integrated exactly
/// with the tetrahedron mass matrix |T|/20 (1 + delta_ab).
void add_volume_force_p1(const mesh::TetMesh& mesh, const DofMap& dofs, const NodalField& b,
                         VectorXd& f);

/// Nodal forces [N] of the stiffness on all 3 n_nodes components (fixed ones included): the
/// internal force K_full u for a displacement field given at the nodes. Used for reactions.
NodalField internal_forces(const mesh::TetMesh& mesh, Materials materials, const NodalField& u);

/// internal_forces summed over the tetrahedra `tets` only: exact at the nodes all of whose
/// tetrahedra are listed (e.g. the nodes with a fixed dof, for their reactions).
NodalField internal_forces(const mesh::TetMesh& mesh, Materials materials, const NodalField& u,
                           std::span<const Index> tets);

/// The node graph of the mesh in CSR arrays: node a's neighbours (the nodes sharing a
/// tetrahedron with it, a itself included) are adj[start[a] .. start[a+1]), ascending.
struct NodeGraph {
  std::vector<SparseIndex> start;  ///< size n_nodes + 1
  std::vector<SparseIndex> adj;
};
NodeGraph node_graph(const mesh::TetMesh& mesh);

/// Vertices of tetrahedron t as columns.
Eigen::Matrix<Real, 3, 4> tet_vertices(const mesh::TetMesh& mesh, Index t);

}  // namespace fricon::fe
