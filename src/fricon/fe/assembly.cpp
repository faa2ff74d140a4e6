#include "fricon/fe/assembly.hpp"

#include <algorithm>

#include "fricon/core/error.hpp"
#include "fricon/fe/p1_element.hpp"

namespace fricon::fe {

Eigen::Matrix<Real, 3, 4> tet_vertices(const mesh::TetMesh& mesh, Index t) {
  Eigen::Matrix<Real, 3, 4> x;
  for (int a = 0; a < 4; ++a)
    x.col(a) = mesh.nodes.col(mesh.tets(a, t));
  return x;
}

NodeGraph node_graph(const mesh::TetMesh& mesh) {
  const Index n = mesh.n_nodes();
  std::vector<std::vector<Index>> lists(static_cast<size_t>(n));
  for (Index t = 0; t < mesh.n_tets(); ++t)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        lists[mesh.tets(a, t)].push_back(mesh.tets(b, t));
  NodeGraph g;
  g.start.assign(static_cast<size_t>(n + 1), 0);
  for (Index i = 0; i < n; ++i) {
    auto& l = lists[i];
    std::sort(l.begin(), l.end());
    l.erase(std::unique(l.begin(), l.end()), l.end());
    g.start[i + 1] = g.start[i] + static_cast<Index>(l.size());
  }
  g.adj.reserve(static_cast<size_t>(g.start[n]));
  for (auto& l : lists) {
    g.adj.insert(g.adj.end(), l.begin(), l.end());
    std::vector<Index>().swap(l);
  }
  return g;
}

SparseMatrix assemble_stiffness(const mesh::TetMesh& mesh, Materials materials,
                                const DofMap& dofs) {
  const NodeGraph graph = node_graph(mesh);
  const Index n = dofs.n_free();

  // Pattern: column dof(b, d) holds rows dof(a, c) for the neighbours a of b, in increasing
  // order because dofs are numbered node-major.
  SparseMatrix K(n, n);
  std::vector<SparseIndex> col_start(static_cast<size_t>(n + 1), 0);
  for (Index b = 0; b < mesh.n_nodes(); ++b)
    for (int d = 0; d < 3; ++d) {
      const Index col = dofs.dof(b, d);
      if (col < 0) continue;
      SparseIndex count = 0;
      for (Index k = graph.start[b]; k < graph.start[b + 1]; ++k)
        for (int c = 0; c < 3; ++c)
          count += dofs.dof(graph.adj[k], c) >= 0;
      col_start[col + 1] = count;
    }
  for (Index j = 0; j < n; ++j)
    col_start[j + 1] += col_start[j];
  K.resizeNonZeros(col_start[n]);
  std::copy(col_start.begin(), col_start.end(), K.outerIndexPtr());
  for (Index b = 0; b < mesh.n_nodes(); ++b)
    for (int d = 0; d < 3; ++d) {
      const Index col = dofs.dof(b, d);
      if (col < 0) continue;
      SparseIndex pos = col_start[col];
      for (Index k = graph.start[b]; k < graph.start[b + 1]; ++k)
        for (int c = 0; c < 3; ++c) {
          const Index row = dofs.dof(graph.adj[k], c);
          if (row >= 0) K.innerIndexPtr()[pos++] = row;
        }
    }
  std::fill(K.valuePtr(), K.valuePtr() + K.nonZeros(), 0.0);

  // Values: add each element matrix into the pattern, locating rows by binary search.
  const SparseIndex* rows = K.innerIndexPtr();
  Real* values = K.valuePtr();
  for (Index t = 0; t < mesh.n_tets(); ++t) {
    const ElementMatrix Ke =
        element_stiffness(tet_vertices(mesh, t), material_of(materials, mesh, t));
    Index local_dof[12];
    for (int a = 0; a < 4; ++a)
      for (int c = 0; c < 3; ++c)
        local_dof[3 * a + c] = dofs.dof(mesh.tets(a, t), c);
    for (int j = 0; j < 12; ++j) {
      const Index col = local_dof[j];
      if (col < 0) continue;
      const SparseIndex* begin = rows + col_start[col];
      const SparseIndex* end = rows + col_start[col + 1];
      for (int i = 0; i < 12; ++i) {
        const Index row = local_dof[i];
        if (row < 0) continue;
        const SparseIndex* it = std::lower_bound(begin, end, static_cast<SparseIndex>(row));
        FRICON_ASSERT(it != end && *it == row,
                      "stiffness pattern misses (" << row << "," << col << ")");
        values[it - rows] += Ke(i, j);
      }
    }
  }
  return K;
}

namespace {
void add_nodal(const DofMap& dofs, Index node, const Vec3& value, VectorXd& f) {
  for (int c = 0; c < 3; ++c) {
    const Index k = dofs.dof(node, c);
    if (k >= 0) f(k) += value(c);
  }
}
void check_load_vector(const DofMap& dofs, const VectorXd& f) {
  FRICON_CHECK(f.size() == dofs.n_free(),
               "load vector of size " << f.size() << ", expected " << dofs.n_free());
}
}  // namespace

void add_traction(const mesh::TetMesh& mesh, const DofMap& dofs, const std::vector<Index>& faces,
                  const Vec3& p, VectorXd& f) {
  check_load_vector(dofs, f);
  for (Index face : faces) {
    const Vec3 share = mesh::face_area(mesh, face) / 3.0 * p;
    for (int v = 0; v < 3; ++v)
      add_nodal(dofs, mesh.faces(v, face), share, f);
  }
}

void add_traction_p1(const mesh::TetMesh& mesh, const DofMap& dofs, const std::vector<Index>& faces,
                     const NodalField& p, VectorXd& f) {
  check_load_vector(dofs, f);
  for (Index face : faces) {
    const Real area = mesh::face_area(mesh, face);
    Vec3 sum = Vec3::Zero();
    for (int v = 0; v < 3; ++v)
      sum += p.col(mesh.faces(v, face));
    // Row a of the mass matrix |T|/12 (1 + delta_ab) applied to p: |T|/12 (p_a + sum).
    for (int v = 0; v < 3; ++v)
      add_nodal(dofs, mesh.faces(v, face), area / 12.0 * (p.col(mesh.faces(v, face)) + sum), f);
  }
}

void add_volume_force(const mesh::TetMesh& mesh, const DofMap& dofs, const Vec3& b, VectorXd& f) {
  check_load_vector(dofs, f);
  for (Index t = 0; t < mesh.n_tets(); ++t) {
    const Vec3 share = std::abs(mesh::tet_volume(mesh, t)) / 4.0 * b;
    for (int a = 0; a < 4; ++a)
      add_nodal(dofs, mesh.tets(a, t), share, f);
  }
}

void add_volume_force_p1(const mesh::TetMesh& mesh, const DofMap& dofs, const NodalField& b,
                         VectorXd& f) {
  check_load_vector(dofs, f);
  for (Index t = 0; t < mesh.n_tets(); ++t) {
    const Real volume = std::abs(mesh::tet_volume(mesh, t));
    Vec3 sum = Vec3::Zero();
    for (int a = 0; a < 4; ++a)
      sum += b.col(mesh.tets(a, t));
    for (int a = 0; a < 4; ++a)
      add_nodal(dofs, mesh.tets(a, t), volume / 20.0 * (b.col(mesh.tets(a, t)) + sum), f);
  }
}

namespace {

// Adds K_T u_T of tetrahedron t to the nodal forces r.
void add_internal_force(const mesh::TetMesh& mesh, Materials materials, const NodalField& u,
                        Index t, NodalField& r) {
  Eigen::Matrix<Real, 12, 1> ue;
  for (int a = 0; a < 4; ++a)
    ue.segment<3>(3 * a) = u.col(mesh.tets(a, t));
  const Eigen::Matrix<Real, 12, 1> re =
      element_stiffness(tet_vertices(mesh, t), material_of(materials, mesh, t)) * ue;
  for (int a = 0; a < 4; ++a)
    r.col(mesh.tets(a, t)) += re.segment<3>(3 * a);
}

}  // namespace

NodalField internal_forces(const mesh::TetMesh& mesh, Materials materials, const NodalField& u) {
  NodalField r = NodalField::Zero(3, mesh.n_nodes());
  for (Index t = 0; t < mesh.n_tets(); ++t)
    add_internal_force(mesh, materials, u, t, r);
  return r;
}

NodalField internal_forces(const mesh::TetMesh& mesh, Materials materials, const NodalField& u,
                           std::span<const Index> tets) {
  NodalField r = NodalField::Zero(3, mesh.n_nodes());
  for (Index t : tets)
    add_internal_force(mesh, materials, u, t, r);
  return r;
}

}  // namespace fricon::fe
