#include "fricon/contact/discretization.hpp"

#include <fmt/format.h>

#include "fricon/contact/radii.hpp"
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

/// c of ContactDiscretization::offset: the P1 integrals over each patch (exact: |T|/3 times the
/// sum of the vertex values on each triangle).
VectorXd constraint_offset(const mesh::TetMesh& mesh, const ContactSurface& s,
                           const Patches& patches, const VectorXd& gap) {
  VectorXd c = VectorXd::Zero(3 * patches.size());
  for (Index p = 0; p < patches.size(); ++p)
    for (Index k : patches.faces[static_cast<size_t>(p)]) {
      const Real third = mesh::face_area(mesh, s.faces[static_cast<size_t>(k)]) / 3.0;
      for (int v = 0; v < 3; ++v) {
        const Index node = s.face_nodes(v, k);
        const Vec3 u = s.prescribed.size() > 0 ? Vec3(s.prescribed.col(node)) : Vec3::Zero();
        c(3 * p) += third * (gap(node) - u.dot(s.n));
        c(3 * p + 1) -= third * u.dot(s.t1);
        c(3 * p + 2) -= third * u.dot(s.t2);
      }
    }
  return c;
}

// Condition (5.1) holds when sigma_min/sigma_max(B) reaches this (check_stability's default).
constexpr Real kMinStabilityRatio = 1e-8;
// Coarsenings of an unstable agglomerate partition before it is refused: each doubles the patch
// size, so four go from patches of a few triangles to a few patches on a typical surface.
constexpr int kMaxCoarsenings = 4;

// One partition of the surface with its B and its stability ratio (not yet judged).
struct Partition {
  Patches patches;
  SparseMatrix B;
  StabilityReport stability;
  bool stable() const { return stability.ratio >= kMinStabilityRatio; }
};

Partition measure_partition(const mesh::TetMesh& mesh, const fe::DofMap& dofs,
                            const ContactSurface& surface, const ContactSpec& spec,
                            Real patch_size) {
  Partition p;
  p.patches = make_patches(spec.patches, mesh, surface, patch_size, spec.where_patches);
  p.B = assemble_b(mesh, dofs, surface, p.patches);
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
                                std::string& note) {
  Real patch_size = spec.patch_size;
  Partition p = measure_partition(mesh, dofs, surface, spec, patch_size);
  std::string tried;
  for (int coarsening = 1; !p.stable() && coarsening <= kMaxCoarsenings; ++coarsening) {
    tried +=
        fmt::format("{}patch_size {:.3g} m: {} patches, ratio {:.2e}", tried.empty() ? "" : "; ",
                    patch_size, p.patches.size(), p.stability.ratio);
    patch_size = 2.0 * mean_patch_diameter(mesh, surface, p.patches);
    p = measure_partition(mesh, dofs, surface, spec, patch_size);
  }
  if (!p.stable())
    throw NumericalError(fmt::format(
        "{}: contact.patches = \"agglomerate\": the partition was refused: it is unstable "
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
                                   const ContactSurface& surface, const ContactSpec& spec) {
  Partition p = measure_partition(mesh, dofs, surface, spec, spec.patch_size);
  if (!p.stable())
    throw NumericalError(fmt::format(
        "{}: contact.patches = \"mesh\": the partition drawn in the mesh (one patch per "
        "elementary entity of '{}') is unstable (condition (5.1) fails): {} patches carry {} "
        "multipliers on {} surface nodes, sigma_min/sigma_max(B) = {:.3e} < {:.1e}. Use "
        "\"agglomerate\" or draw a coarser partition in Gmsh (fewer, larger surfaces, each with "
        "nodes of its own that are not clamped).",
        spec.where_patches, surface.tag, p.patches.size(), 3 * p.patches.size(), surface.n_nodes(),
        p.stability.ratio, kMinStabilityRatio));
  return p;
}

// Patches, B and its checked stability of d.surface, the partition coarsened if need be.
void partition_stably(const mesh::TetMesh& mesh, const fe::DofMap& dofs, const ContactSpec& spec,
                      ContactDiscretization& d) {
  Partition p;
  switch (spec.patches) {
    case PatchKind::Agglomerate:
      p = coarsened_agglomerate(mesh, dofs, d.surface, spec, d.partition_note);
      break;
    case PatchKind::Mesh:
      p = checked_entity_partition(mesh, dofs, d.surface, spec);
      break;
    case PatchKind::Chessboard:
      p.patches = make_patches(spec.patches, mesh, d.surface, spec.patch_size, spec.where_patches);
      p.B = assemble_b(mesh, dofs, d.surface, p.patches);
      p.stability = check_stability(p.B, spec.where_patches, kMinStabilityRatio);
      break;
  }
  d.patches = std::move(p.patches);
  d.B = std::move(p.B);
  d.stability = p.stability;
}

}  // namespace

ContactDiscretization discretize_contact(const mesh::TetMesh& mesh, const fe::DofMap& dofs,
                                         const ContactSpec& spec) {
  ContactDiscretization d;
  d.surface = make_contact_surface(mesh, dofs, spec.boundary, spec.where_boundary, spec.obstacle);
  d.surface.prescribed = prescribed_on_surface(d.surface, spec.prescribed);
  partition_stably(mesh, dofs, spec, d);
  d.slip_bound = VectorXd::Constant(d.surface.n_nodes(), spec.slip_bound);
  d.gap = spec.obstacle ? initial_gap(mesh, d.surface, *spec.obstacle, spec.where_obstacle)
                        : VectorXd::Zero(d.surface.n_nodes());
  d.offset = constraint_offset(mesh, d.surface, d.patches, d.gap);
  d.dofs = dofs.free_dofs(d.surface.nodes);
  d.radius_integration = kRadiusIntegration;
  return d;
}

}  // namespace fricon::contact
