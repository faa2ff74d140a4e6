#include "fricon/fe/assembly.hpp"

#include <algorithm>

#include "fricon/core/error.hpp"
#include "fricon/fe/element.hpp"
#include "fricon/fe/stiffness.hpp"

namespace fricon::fe {

NodeGraph node_graph(const mesh::TetMesh& mesh) {
  const Index n = mesh.n_nodes();
  std::vector<std::vector<Index>> lists(static_cast<size_t>(n));
  for (Index t = 0; t < mesh.n_tets(); ++t)
    for (int a = 0; a < mesh.nodes_per_tet(); ++a)
      for (int b = 0; b < mesh.nodes_per_tet(); ++b)
        lists[mesh.tet_node(t, a)].push_back(mesh.tet_node(t, b));
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
  const Element& element = elements_of(mesh).cell;
  const int n_dofs = 3 * element.n_nodes();
  for (Index t = 0; t < mesh.n_tets(); ++t) {
    const ElementMatrix Ke =
        element_stiffness(element, tet_points(mesh, t), material_of(materials, mesh, t));
    Index local_dof[kMaxElementDofs];
    for (int a = 0; a < element.n_nodes(); ++a)
      for (int c = 0; c < 3; ++c)
        local_dof[3 * a + c] = dofs.dof(mesh.tet_node(t, a), c);
    for (int j = 0; j < n_dofs; ++j) {
      const Index col = local_dof[j];
      if (col < 0) continue;
      const SparseIndex* begin = rows + col_start[col];
      const SparseIndex* end = rows + col_start[col + 1];
      for (int i = 0; i < n_dofs; ++i) {
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

// The integrals int_T phi_a dS of the face element (with_field false) or sum_b int_T phi_a phi_b
// p_b dS of a nodal field p (true) over triangle f, added to f at its nodes. Likewise
// add_cell_load over tetrahedron t.
void add_face_load(const mesh::TetMesh& mesh, const DofMap& dofs, Index face, const Vec3& p,
                   const NodalField* field, VectorXd& f) {
  const Element& element = elements_of(mesh).face;
  const Tabulation& points = element.mass_points();
  const ElementNodes x = face_points(mesh, face);
  for (Index q = 0; q < points.size(); ++q) {
    const ShapeValues& N = points.values[static_cast<size_t>(q)];
    const Real dS =
        points.weight(q) * map_face(x, points.derivatives[static_cast<size_t>(q)]).area_element;
    Vec3 value = p;
    if (field != nullptr) {
      value.setZero();
      for (int b = 0; b < element.n_nodes(); ++b)
        value += N(b) * field->col(mesh.face_node(face, b));
    }
    for (int a = 0; a < element.n_nodes(); ++a)
      add_nodal(dofs, mesh.face_node(face, a), dS * N(a) * value, f);
  }
}

void add_cell_load(const mesh::TetMesh& mesh, const DofMap& dofs, Index t, const Vec3& b,
                   const NodalField* field, VectorXd& f) {
  const Element& element = elements_of(mesh).cell;
  const Tabulation& points = element.mass_points();
  const ElementNodes x = tet_points(mesh, t);
  for (Index q = 0; q < points.size(); ++q) {
    const ShapeValues& N = points.values[static_cast<size_t>(q)];
    const Real dV = points.weight(q) * map_cell(x, points.derivatives[static_cast<size_t>(q)]).det;
    Vec3 value = b;
    if (field != nullptr) {
      value.setZero();
      for (int c = 0; c < element.n_nodes(); ++c)
        value += N(c) * field->col(mesh.tet_node(t, c));
    }
    for (int a = 0; a < element.n_nodes(); ++a)
      add_nodal(dofs, mesh.tet_node(t, a), dV * N(a) * value, f);
  }
}
}  // namespace

void add_traction(const mesh::TetMesh& mesh, const DofMap& dofs, const std::vector<Index>& faces,
                  const Vec3& p, VectorXd& f) {
  check_load_vector(dofs, f);
  for (Index face : faces)
    add_face_load(mesh, dofs, face, p, nullptr, f);
}

void add_traction_field(const mesh::TetMesh& mesh, const DofMap& dofs,
                        const std::vector<Index>& faces, const NodalField& p, VectorXd& f) {
  check_load_vector(dofs, f);
  for (Index face : faces)
    add_face_load(mesh, dofs, face, Vec3::Zero(), &p, f);
}

void add_volume_force(const mesh::TetMesh& mesh, const DofMap& dofs, const Vec3& b, VectorXd& f) {
  check_load_vector(dofs, f);
  for (Index t = 0; t < mesh.n_tets(); ++t)
    add_cell_load(mesh, dofs, t, b, nullptr, f);
}

void add_volume_force_field(const mesh::TetMesh& mesh, const DofMap& dofs, const NodalField& b,
                            VectorXd& f) {
  check_load_vector(dofs, f);
  for (Index t = 0; t < mesh.n_tets(); ++t)
    add_cell_load(mesh, dofs, t, Vec3::Zero(), &b, f);
}

namespace {

// Adds K_T u_T of tetrahedron t to the nodal forces r.
void add_internal_force(const mesh::TetMesh& mesh, Materials materials, const NodalField& u,
                        Index t, NodalField& r) {
  const Element& element = elements_of(mesh).cell;
  ElementVector ue(3 * element.n_nodes());
  for (int a = 0; a < element.n_nodes(); ++a)
    ue.segment<3>(3 * a) = u.col(mesh.tet_node(t, a));
  const ElementVector re =
      element_stiffness(element, tet_points(mesh, t), material_of(materials, mesh, t)) * ue;
  for (int a = 0; a < element.n_nodes(); ++a)
    r.col(mesh.tet_node(t, a)) += re.segment<3>(3 * a);
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
