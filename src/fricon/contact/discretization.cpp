#include "fricon/contact/discretization.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include <fmt/format.h>

#include "fricon/contact/radii.hpp"
#include "fricon/contact/surface_integrals.hpp"
#include "fricon/core/error.hpp"

namespace fricon::contact {

namespace {

/// The surface nodes' columns of the prescribed field (empty stays empty).
Eigen::Matrix<Real, 3, Eigen::Dynamic> prescribed_on_surface(
    const ContactSurface& s, const Eigen::Matrix<Real, 3, Eigen::Dynamic>& prescribed) {
  Eigen::Matrix<Real, 3, Eigen::Dynamic> p;
  if (prescribed.size() == 0 || prescribed.isZero(0.0)) return p;
  p.resize(3, s.n_nodes());
  for (Index k = 0; k < s.n_nodes(); ++k)
    p.col(k) = prescribed.col(s.nodes[static_cast<size_t>(k)]);
  return p;
}

/// The gap part G of ContactDiscretization::offset: per patch int_R gap dS in its normal row, the
/// gap interpolated by the face element: sum_a g_a int_T phi_a dS (surface_integrals.hpp).
VectorXd gap_offset(const mesh::TetMesh& mesh, const ContactSurface& s, const Patches& patches,
                    const VectorXd& gap) {
  VectorXd c = VectorXd::Zero(3 * patches.size());
  for (Index p = 0; p < patches.size(); ++p)
    for (Index k : patches.faces[static_cast<size_t>(p)])
      c(3 * p) += face_integrals(mesh, s, k).shape.dot(gap(s.face_nodes.col(k)));
  return c;
}

/// The prescribed part P of ContactDiscretization::offset: the patch integrals of the prescribed
/// displacement in the rows' directions (slave: patch_row_weights), minus the
/// master's through the mortar integrals against a body (theory.md §2.8); c = G - P vec(u_p).
SparseMatrix prescribed_offset(const mesh::TetMesh& mesh, const ContactSurface& s,
                               const Patches& patches, const Frames& frames,
                               const std::vector<PatchRowWeights>& weights,
                               const SparseMatrix& mortar) {
  std::vector<Eigen::Triplet<Real, SparseIndex>> entries;
  for (Index p = 0; p < patches.size(); ++p) {
    const PatchRowWeights& w = weights[static_cast<size_t>(p)];
    for (size_t i = 0; i < w.nodes.size(); ++i) {
      const Index node = s.nodes[static_cast<size_t>(w.nodes[i])];
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
          entries.emplace_back(3 * p + r, 3 * node + c, w.W[i](r, c));
    }
  }
  for (Index a = 0; a < mortar.outerSize(); ++a)
    for (SparseMatrix::InnerIterator it(mortar, a); it; ++it) {
      const Mat3 dirs = frames.rows(it.row());
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
          entries.emplace_back(3 * it.row() + r, 3 * a + c, -it.value() * dirs(r, c));
    }
  SparseMatrix P(3 * patches.size(), 3 * mesh.n_nodes());
  P.setFromTriplets(entries.begin(), entries.end());
  return P;
}

// Condition (5.1) holds when sigma_min/sigma_max(B) reaches this (check_stability's default).
constexpr Real kMinStabilityRatio = 1e-8;
// Coarsenings of an unstable agglomerate partition before it is refused: each doubles the patch
// size, so four go from patches of a few triangles to a few patches on a typical surface.
constexpr int kMaxCoarsenings = 4;

// Against a body: the master, located once, and how far along a normal it is looked for. Against
// a plane: no master.
struct Reach {
  std::shared_ptr<const SurfaceLocator> master;
  Real distance = 0.0;  // [m]
};

// One partition of the surface with its frames, mortar integrals, B and stability ratio (not
// yet judged).
struct Partition {
  Patches patches;
  Frames frames;
  SparseMatrix mortar;  // against a body only
  Real coverage = 1.0;  // against a body only
  SparseMatrix B;
  StabilityReport stability;
  bool stable() const { return stability.ratio >= kMinStabilityRatio; }
};

// The frames, mortar integrals and B of p.patches.
void couple(const mesh::TetMesh& mesh, const fe::DofMap& dofs, const ContactSurface& surface,
            const Reach& reach, Partition& p) {
  p.frames = patch_frames(mesh, surface, p.patches);
  if (reach.master)
    p.mortar = mortar_matrix(mesh, surface, p.patches, p.frames, *reach.master, reach.distance,
                             p.coverage);
  p.B = assemble_b(mesh, dofs, surface, p.patches, p.frames, reach.master ? &p.mortar : nullptr);
}

Partition measure_partition(const mesh::TetMesh& mesh, const fe::DofMap& dofs,
                            const ContactSurface& surface, const ContactSpec& spec,
                            const Reach& reach, Real patch_size) {
  Partition p;
  p.patches = make_patches(spec.patches, mesh, surface, patch_size, spec.where_patches);
  couple(mesh, dofs, surface, reach, p);
  p.stability = check_stability(p.B, spec.where_patches, /*min_ratio=*/0.0);
  return p;
}

Real mean_patch_diameter(const mesh::TetMesh& mesh, const ContactSurface& surface,
                         const Patches& patches) {
  Real sum = 0.0;
  for (Index p = 0; p < patches.size(); ++p)
    sum += patch_diameter(mesh, surface, patches, p);
  return sum / static_cast<Real>(patches.size());
}

// An agglomerate partition, rebuilt with twice its mean patch diameter as patch size while it is
// unstable, at most kMaxCoarsenings times; `note` says what was done.
Partition coarsened_agglomerate(const mesh::TetMesh& mesh, const fe::DofMap& dofs,
                                const ContactSurface& surface, const ContactSpec& spec,
                                const Reach& reach, std::string& note) {
  Real patch_size = spec.patch_size;
  Partition p = measure_partition(mesh, dofs, surface, spec, reach, patch_size);
  std::string tried;
  for (int coarsening = 1; !p.stable() && coarsening <= kMaxCoarsenings; ++coarsening) {
    tried +=
        fmt::format("{}patch_size {:.3g} m: {} patches, ratio {:.2e}", tried.empty() ? "" : "; ",
                    patch_size, p.patches.size(), p.stability.ratio);
    patch_size = 2.0 * mean_patch_diameter(mesh, surface, p.patches);
    p = measure_partition(mesh, dofs, surface, spec, reach, patch_size);
  }
  if (!p.stable())
    throw NumericalError(fmt::format(
        "{} = \"agglomerate\": the partition was refused: it is unstable "
        "(condition (5.1) fails) after {} coarsenings (tried {}; last patch_size {:.3g} m: {} "
        "patches, sigma_min/sigma_max(B) = {:.3e} < {:.1e}). Every patch needs contact nodes that "
        "are not clamped.",
        spec.where_patches, kMaxCoarsenings, tried, patch_size, p.patches.size(), p.stability.ratio,
        kMinStabilityRatio));
  if (!tried.empty())
    note = fmt::format(
        "agglomerate partition coarsened (unstable: {}) to patch_size {:.3g} m: {} patches, "
        "ratio {:.2e}",
        tried, patch_size, p.patches.size(), p.stability.ratio);
  return p;
}

// The mesh file's partition, refused with advice when unstable.
Partition checked_entity_partition(const mesh::TetMesh& mesh, const fe::DofMap& dofs,
                                   const ContactSurface& surface, const ContactSpec& spec,
                                   const Reach& reach) {
  Partition p = measure_partition(mesh, dofs, surface, spec, reach, spec.patch_size);
  if (!p.stable())
    throw NumericalError(fmt::format(
        "{} = \"mesh\": the partition drawn in the mesh (one patch per "
        "elementary entity of '{}') is unstable (condition (5.1) fails): {} patches carry {} "
        "multipliers on {} surface nodes, sigma_min/sigma_max(B) = {:.3e} < {:.1e}. Use "
        "\"agglomerate\" or draw a coarser partition in Gmsh (fewer, larger surfaces, each with "
        "nodes of its own that are not clamped).",
        spec.where_patches, surface.tag, p.patches.size(), 3 * p.patches.size(), surface.n_nodes(),
        p.stability.ratio, kMinStabilityRatio));
  return p;
}

// Patches, frames, B and its checked stability of d.surface, the partition coarsened if need be.
Partition partition_stably(const mesh::TetMesh& mesh, const fe::DofMap& dofs,
                           const ContactSpec& spec, const Reach& reach, ContactDiscretization& d) {
  Partition p;
  switch (spec.patches) {
    case PatchKind::Agglomerate:
      p = coarsened_agglomerate(mesh, dofs, d.surface, spec, reach, d.partition_note);
      break;
    case PatchKind::Mesh:
      p = checked_entity_partition(mesh, dofs, d.surface, spec, reach);
      break;
    case PatchKind::Chessboard:
      p.patches = make_patches(spec.patches, mesh, d.surface, spec.patch_size, spec.where_patches);
      couple(mesh, dofs, d.surface, reach, p);
      p.stability = check_stability(p.B, spec.where_patches, kMinStabilityRatio);
      break;
  }
  require_active_patches(d.surface, p.patches, p.B, spec.where_patches);
  return p;
}

// The surface and the gap of the pair: against the plane (or the flat surface's own), or against
// a master surface (master_surface.hpp), whose reach it returns.
Reach make_surface(const mesh::TetMesh& mesh, const fe::DofMap& dofs, const ContactSpec& spec,
                   ContactDiscretization& d) {
  PairInfo& pair = d.pairs.emplace_back();
  pair.key = spec.key;
  pair.boundary = spec.boundary;
  if (spec.master) {
    SlaveSurface slave = make_slave_surface(mesh, dofs, spec.boundary, spec.where_boundary,
                                            *spec.master, spec.prescribed);
    d.surface = std::move(slave.surface);
    d.surface.prescribed = prescribed_on_surface(d.surface, spec.prescribed);
    d.gap = std::move(slave.gap);
    pair.master = spec.master->boundary;
    pair.n_tag_faces = slave.n_tag_faces;
    pair.search_distance = slave.search_distance;
    pair.master_element_size = slave.master_element_size;
    return {std::move(slave.master), slave.search_distance};
  }
  if (!spec.obstacle) {
    d.surface = make_contact_surface(mesh, dofs, spec.boundary, spec.where_boundary);
    d.gap = VectorXd::Zero(d.surface.n_nodes());
  } else {
    const RigidContact rigid{spec.obstacle.get(), spec.linearized_displacement,
                             spec.deformation.size() > 0 ? &spec.deformation : nullptr};
    d.surface = make_contact_surface(mesh, dofs, spec.boundary, spec.where_boundary, &rigid);
    check_outside_obstacle(mesh, d.surface, *spec.obstacle, spec.where_obstacle);
    d.gap = obstacle_gap(mesh, d.surface, rigid);
    pair.obstacle = spec.obstacle;
    pair.obstacle_displacement = spec.obstacle_displacement;
    if (!spec.obstacle_displacement.isZero(0.0))
      d.surface.master_prescribed = spec.obstacle_displacement.replicate(1, d.surface.n_nodes());
  }
  d.surface.prescribed = prescribed_on_surface(d.surface, spec.prescribed);
  pair.n_tag_faces = static_cast<Index>(d.surface.faces.size());
  return {};
}

// The nodes the rows of B touch: the surface's, and the master's against a body.
std::vector<Index> coupled_nodes(const ContactSurface& s, const SparseMatrix& mortar) {
  std::vector<Index> nodes = s.nodes;
  for (Index a = 0; a < mortar.outerSize(); ++a)
    if (SparseMatrix::InnerIterator(mortar, a)) nodes.push_back(a);
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

}  // namespace

ContactDiscretization discretize_contact(const mesh::TetMesh& mesh, const fe::DofMap& dofs,
                                         const ContactSpec& spec) {
  ContactDiscretization d;
  const Reach reach = make_surface(mesh, dofs, spec, d);
  d.pairs.front().n = d.surface.n;
  d.pairs.front().t1 = d.surface.t1;
  d.pairs.front().t2 = d.surface.t2;
  Partition p = partition_stably(mesh, dofs, spec, reach, d);
  d.patches = std::move(p.patches);
  d.B = std::move(p.B);
  d.stability = p.stability;
  d.patch_frames = std::move(p.frames);
  d.patch_pair.assign(static_cast<size_t>(d.patches.size()), 0);
  d.pairs.front().stability = p.stability;
  d.pairs.front().master_coverage = p.coverage;
  d.slip_bound = VectorXd::Constant(d.surface.n_nodes(), spec.slip_bound);
  const std::vector<PatchRowWeights> weights =
      patch_row_weights(mesh, d.surface, d.patches, d.patch_frames);
  for (const PatchRowWeights& w : weights)
    d.frame_integrals.push_back(w.integral);
  d.gap_offset = gap_offset(mesh, d.surface, d.patches, d.gap);
  d.prescribed_offset =
      prescribed_offset(mesh, d.surface, d.patches, d.patch_frames, weights, p.mortar);
  d.offset = constraint_offset(d, spec.prescribed);
  d.dofs = dofs.free_dofs(coupled_nodes(d.surface, p.mortar));
  d.radius_integration = kRadiusIntegration;
  return d;
}

namespace {

using Matrix3X = Eigen::Matrix<Real, 3, Eigen::Dynamic>;

/// [a b] for a of na columns and b of nb, each of which may be empty (meaning zero); empty when
/// both are.
Matrix3X stack_columns(const Matrix3X& a, Index na, const Matrix3X& b, Index nb) {
  if (a.size() == 0 && b.size() == 0) return Matrix3X();
  Matrix3X out = Matrix3X::Zero(3, na + nb);
  if (a.size() > 0) out.leftCols(na) = a;
  if (b.size() > 0) out.rightCols(nb) = b;
  return out;
}

VectorXd stack(const VectorXd& a, const VectorXd& b) {
  VectorXd out(a.size() + b.size());
  out << a, b;
  return out;
}

template <typename Sparse>
Sparse stack_rows(const Sparse& a, const Sparse& b, Index cols) {
  std::vector<Eigen::Triplet<Real, SparseIndex>> t;
  for (int part = 0; part < 2; ++part) {
    const Sparse& m = part == 0 ? a : b;
    const Index shift = part == 0 ? 0 : a.rows();
    for (Index o = 0; o < m.outerSize(); ++o)
      for (typename Sparse::InnerIterator it(m, o); it; ++it)
        t.emplace_back(shift + it.row(), it.col(), it.value());
  }
  Sparse out(a.rows() + b.rows(), cols);
  out.setFromTriplets(t.begin(), t.end());
  return out;
}

Frames stack(const Frames& a, const Frames& b) {
  Frames f;
  f.n = stack_columns(a.n, a.size(), b.n, b.size());
  f.t1 = stack_columns(a.t1, a.size(), b.t1, b.size());
  f.t2 = stack_columns(a.t2, a.size(), b.t2, b.size());
  return f;
}

/// b's surface appended to a's: nodes (a node of two pairs appears twice), triangles, frames,
/// master rows; a's n, t1, t2 kept.
void append_surface(ContactSurface& a, const ContactSurface& b, Index pair, Index mesh_nodes) {
  const Index node_shift = a.n_nodes();
  a.tag += ", " + b.tag;
  a.faces.insert(a.faces.end(), b.faces.begin(), b.faces.end());
  a.nodes.insert(a.nodes.end(), b.nodes.begin(), b.nodes.end());
  a.fixed.insert(a.fixed.end(), b.fixed.begin(), b.fixed.end());
  a.contact_node.insert(a.contact_node.end(), b.contact_node.begin(), b.contact_node.end());
  Eigen::Matrix<Index, Eigen::Dynamic, Eigen::Dynamic> faces(
      a.face_nodes.rows(), a.face_nodes.cols() + b.face_nodes.cols());
  faces << a.face_nodes, (b.face_nodes.array() + node_shift).matrix();
  a.face_nodes = std::move(faces);
  a.area += b.area;
  a.prescribed = stack_columns(a.prescribed, node_shift, b.prescribed, b.n_nodes());
  a.master_prescribed =
      stack_columns(a.master_prescribed, node_shift, b.master_prescribed, b.n_nodes());
  a.node_frames = stack(a.node_frames, b.node_frames);
  a.frames_vary = a.frames_vary || b.frames_vary;
  using Weights = decltype(a.master);
  const Weights none_a = a.master.size() > 0 ? a.master : Weights(node_shift, mesh_nodes);
  const Weights none_b = b.master.size() > 0 ? b.master : Weights(b.n_nodes(), mesh_nodes);
  a.master = (a.master.size() > 0 || b.master.size() > 0) ? stack_rows(none_a, none_b, mesh_nodes)
                                                          : Weights();
  a.node_pair.insert(a.node_pair.end(), static_cast<size_t>(b.n_nodes()), pair);
}

}  // namespace

namespace {

/// Per multiplier row: int_R u_o . d dS [m^3] for the translation u_o of each pair's rigid
/// obstacle (frame_integrals[p] times it): where disc has it, or `obstacles` (one per pair) when
/// given; zero against a body.
VectorXd obstacle_integrals(const ContactDiscretization& disc,
                            const std::vector<Vec3>* obstacles = nullptr) {
  VectorXd out = VectorXd::Zero(disc.n_dual());
  for (Index p = 0; p < disc.n_patches(); ++p) {
    const auto i = static_cast<size_t>(disc.patch_pair[static_cast<size_t>(p)]);
    if (!disc.pairs[i].obstacle) continue;
    const Vec3& d = obstacles != nullptr ? obstacles->at(i) : disc.pairs[i].obstacle_displacement;
    out.segment<3>(3 * p) = disc.frame_integrals[static_cast<size_t>(p)] * d;
  }
  return out;
}

/// The obstacles' displacements at the surface nodes (ContactSurface::master_prescribed of the
/// rigid pairs; the body pairs' rows are left as they are): empty when nothing moves.
void obstacle_node_displacements(ContactDiscretization& disc) {
  ContactSurface& s = disc.surface;
  bool moves = false;
  for (const PairInfo& pair : disc.pairs)
    moves = moves || (pair.obstacle && !pair.obstacle_displacement.isZero(0.0));
  if (!moves) {
    if (s.master.size() == 0) s.master_prescribed.resize(3, 0);
    return;
  }
  if (s.master_prescribed.size() == 0) s.master_prescribed.setZero(3, s.n_nodes());
  for (Index k = 0; k < s.n_nodes(); ++k) {
    const PairInfo& pair = disc.pairs[static_cast<size_t>(s.node_pair[static_cast<size_t>(k)])];
    if (pair.obstacle) s.master_prescribed.col(k) = pair.obstacle_displacement;
  }
}

}  // namespace

VectorXd constraint_offset(const ContactDiscretization& disc,
                           const Eigen::Matrix<Real, 3, Eigen::Dynamic>& prescribed) {
  const VectorXd moved = disc.gap_offset + obstacle_integrals(disc);
  if (prescribed.size() == 0) return moved;
  FRICON_CHECK(3 * prescribed.cols() == disc.prescribed_offset.cols(),
               "constraint_offset: a prescribed field of " << prescribed.cols() << " nodes");
  const Eigen::Map<const VectorXd> u(prescribed.data(), prescribed.size());
  return moved - disc.prescribed_offset * u;
}

void set_prescribed(ContactDiscretization& disc,
                    const Eigen::Matrix<Real, 3, Eigen::Dynamic>& prescribed,
                    const std::vector<Vec3>* obstacle_displacements) {
  ContactSurface& s = disc.surface;
  s.prescribed = prescribed_on_surface(s, prescribed);
  if (s.master.size() > 0)
    s.master_prescribed = prescribed.size() > 0
                              ? Eigen::Matrix<Real, 3, Eigen::Dynamic>(
                                    (s.master * prescribed.transpose()).transpose())
                              : Eigen::Matrix<Real, 3, Eigen::Dynamic>();
  if (obstacle_displacements) {
    FRICON_CHECK(obstacle_displacements->size() == disc.pairs.size(),
                 "set_prescribed: " << obstacle_displacements->size() << " obstacle displacements");
    for (size_t i = 0; i < disc.pairs.size(); ++i)
      disc.pairs[i].obstacle_displacement =
          disc.pairs[i].obstacle ? (*obstacle_displacements)[i] : Vec3(Vec3::Zero());
  }
  obstacle_node_displacements(disc);
  disc.offset = constraint_offset(disc, prescribed);
}

VectorXd patch_integrals(const ContactDiscretization& disc, const VectorXd& w,
                         const Eigen::Matrix<Real, 3, Eigen::Dynamic>& prescribed,
                         const std::vector<Vec3>& obstacles) {
  FRICON_CHECK(obstacles.size() == disc.pairs.size(),
               "patch_integrals: " << obstacles.size() << " obstacle displacements");
  VectorXd d = disc.B * w - obstacle_integrals(disc, &obstacles);
  if (prescribed.size() == 0) return d;
  const Eigen::Map<const VectorXd> up(prescribed.data(), prescribed.size());
  return d + disc.prescribed_offset * up;
}

VectorXd patch_integrals(const ContactDiscretization& disc, const VectorXd& w,
                         const Eigen::Matrix<Real, 3, Eigen::Dynamic>& prescribed) {
  VectorXd d = disc.B * w - obstacle_integrals(disc);
  if (prescribed.size() == 0) return d;
  const Eigen::Map<const VectorXd> up(prescribed.data(), prescribed.size());
  return d + disc.prescribed_offset * up;
}

LinearizationError linearization_error(const mesh::TetMesh& mesh, const ContactDiscretization& disc,
                                       const Eigen::Matrix<Real, 3, Eigen::Dynamic>& u,
                                       const std::vector<bool>& in_contact) {
  const ContactSurface& s = disc.surface;
  LinearizationError e;
  for (Index k = 0; k < s.n_nodes(); ++k) {
    const PairInfo& pair = disc.pairs[static_cast<size_t>(s.node_pair[static_cast<size_t>(k)])];
    if (!pair.obstacle || !in_contact[static_cast<size_t>(k)]) continue;
    const Index a = s.nodes[static_cast<size_t>(k)];
    const Vec3 relative = u.col(a) - pair.obstacle_displacement;
    const Real wn = s.node_frames.n.col(k).dot(relative);
    const Real linearized = disc.gap(k) - wn;
    const Real exact = pair.obstacle->closest(mesh.nodes.col(a) + relative).distance;
    e.change = std::max(e.change, std::abs(exact - linearized));
    e.scale = std::max(e.scale, std::abs(wn));
  }
  return e;
}

ContactDiscretization merge_pairs(std::vector<ContactDiscretization> pairs) {
  FRICON_CHECK(!pairs.empty(), "merge_pairs: no pair");
  ContactDiscretization d = std::move(pairs.front());
  for (size_t i = 1; i < pairs.size(); ++i) {
    const ContactDiscretization& b = pairs[i];
    const auto pair = static_cast<Index>(i);
    const Index face_shift = static_cast<Index>(d.surface.faces.size());
    const Index mesh_nodes = std::max(b.surface.master.cols(), d.surface.master.cols());
    append_surface(d.surface, b.surface, pair, mesh_nodes);
    for (const auto& faces : b.patches.faces) {
      std::vector<Index> shifted = faces;
      for (Index& k : shifted)
        k += face_shift;
      d.patches.faces.push_back(std::move(shifted));
    }
    d.patches.area = stack(d.patches.area, b.patches.area);
    d.patches.centroid = stack_columns(d.patches.centroid, d.patches.size() - b.patches.size(),
                                       b.patches.centroid, b.patches.size());
    d.patch_frames = stack(d.patch_frames, b.patch_frames);
    d.frame_integrals.insert(d.frame_integrals.end(), b.frame_integrals.begin(),
                             b.frame_integrals.end());
    d.patch_pair.insert(d.patch_pair.end(), static_cast<size_t>(b.patches.size()), pair);
    d.B = stack_rows(d.B, b.B, d.B.cols());
    d.slip_bound = stack(d.slip_bound, b.slip_bound);
    d.gap = stack(d.gap, b.gap);
    d.offset = stack(d.offset, b.offset);
    d.gap_offset = stack(d.gap_offset, b.gap_offset);
    d.prescribed_offset =
        stack_rows(d.prescribed_offset, b.prescribed_offset, d.prescribed_offset.cols());
    std::vector<Index> dofs = d.dofs;
    dofs.insert(dofs.end(), b.dofs.begin(), b.dofs.end());
    std::sort(dofs.begin(), dofs.end());
    dofs.erase(std::unique(dofs.begin(), dofs.end()), dofs.end());
    d.dofs = std::move(dofs);
    if (b.stability.ratio < d.stability.ratio) d.stability = b.stability;
    if (!b.partition_note.empty())
      d.partition_note +=
          (d.partition_note.empty() ? "" : "; ") + b.pairs.front().key + ": " + b.partition_note;
    d.pairs.push_back(b.pairs.front());
  }
  return d;
}

}  // namespace fricon::contact
