#include "fricon/driver/floating_bodies.hpp"

#include <fmt/format.h>

#include "fricon/core/error.hpp"
#include "fricon/driver/contact_solver.hpp"

namespace fricon::driver {

namespace {

// A motion counts as a force rather than a moment when its translation moves the body's
// farthest point at least this share as much as its rotation does.
constexpr Real kTranslationShare = 0.5;

// The columns of R of floating body `body` within an m-vector over every free motion.
VectorXd block_of(const fe::FloatingBody& body, const VectorXd& v) {
  return v.segment(body.first_column, body.n_motions());
}

// A unit direction in words, components below a thousandth of the largest shown as 0.
std::string vector_text(Vec3 v) {
  const Real largest = v.cwiseAbs().maxCoeff();
  for (int i = 0; i < 3; ++i)
    if (std::abs(v(i)) < 1e-3 * largest) v(i) = 0.0;
  return fmt::format("({:.3g}, {:.3g}, {:.3g})", v(0), v(1), v(2));
}

}  // namespace

std::string body_line(const BodyReport& body) {
  if (body.free_motions.empty())
    return fmt::format("{}: held by its Dirichlet conditions", body.description);
  std::string motions;
  for (std::size_t j = 0; j < body.free_motions.size(); ++j) {
    const std::string& name = body.free_motions[j];
    const std::string_view unit = name.starts_with("translation") ? " m"
                                  : name.starts_with("rotation")  ? " rad"
                                                                  : "";
    motions += fmt::format("{}{}", j == 0 ? "" : ", ", name);
    if (j < body.amplitudes.size()) motions += fmt::format(" = {:.4e}{}", body.amplitudes[j], unit);
  }
  std::string undetermined;
  for (std::size_t j = 0; j < body.undetermined.size(); ++j)
    undetermined += fmt::format("{}{}", j == 0 ? "" : ", ", body.undetermined[j]);
  return fmt::format(
      "{}: floats, held by contact in its free motions {}{}", body.description, motions,
      undetermined.empty()
          ? std::string()
          : fmt::format("; no contact force resists {} (frictionless): the solution is the one "
                        "of least norm in them",
                        undetermined));
}

std::vector<BodyReport> describe_bodies(const Model& model) {
  std::vector<BodyReport> out;
  for (Index b = 0; b < model.bodies.n_bodies(); ++b) {
    BodyReport r;
    r.index = b;
    r.description = mesh::describe_body(model.mesh, model.bodies, b);
    out.push_back(std::move(r));
  }
  for (const fe::FloatingBody& body : model.floating.bodies)
    for (Index j = 0; j < body.n_motions(); ++j)
      out[static_cast<size_t>(body.body)].free_motions.push_back(body.motion_name(j));
  return out;
}

std::vector<BodyReport> describe_bodies(const Model& model, const VectorXd& u,
                                        const MatrixXd& undetermined) {
  std::vector<BodyReport> out = describe_bodies(model);
  if (model.floating.empty() || u.size() != model.floating.R.rows()) return out;
  for (const fe::FloatingBody& body : model.floating.bodies) {
    BodyReport& r = out[static_cast<size_t>(body.body)];
    // The body's columns of R are zero outside it: R_b^T R_b a = R_b^T u.
    const MatrixXd R_b = MatrixXd(model.floating.R.middleCols(body.first_column, body.n_motions()));
    const VectorXd a = (R_b.transpose() * R_b).ldlt().solve(R_b.transpose() * u);
    r.amplitudes.assign(a.data(), a.data() + a.size());
    const Index n_undetermined =
        undetermined.rows() == model.floating.n_motions() ? undetermined.cols() : 0;
    for (Index k = 0; k < n_undetermined; ++k) {
      const VectorXd d = block_of(body, undetermined.col(k));
      if (d.norm() <= 1e-12 * undetermined.col(k).norm()) continue;
      fe::MotionCoefficients c = body.motions * d;
      c /= c.cwiseAbs().maxCoeff();
      for (Index i = 0; i < 6; ++i)
        if (std::abs(c(i)) < 1e-9) c(i) = 0.0;
      r.undetermined.push_back(fe::describe_motion(c));
    }
  }
  return out;
}

void check_balance(const Problem& problem, const Model& model,
                   const contact::ContactDiscretization& disc) {
  if (model.floating.empty() || problem.loading.steps > 1) return;
  const auto bounds = make_slip_bounds(problem, model.mesh, disc);
  if (bounds->uses_pressure()) return;
  qp::SeparableConstraints c = qp::SeparableConstraints::contact_layout(disc.n_patches());
  c.set_disc_radii(
      bounds->radii(1, VectorXd::Zero(disc.surface.n_nodes()), VectorXd::Zero(disc.n_patches())));
  const SparseMatrix& R = model.floating.R;
  const qp::EqualityConstraint balance{SparseMatrix(R.transpose() * disc.B.transpose()),
                                       R.transpose() * model.f};
  if (auto certificate = qp::balance_certificate(balance, c, problem.solver.qp.rel_tolerance))
    refuse_unbalanced_load(problem, model, *certificate);
}

void refuse_unbalanced_load(const Problem& problem, const Model& model,
                            const qp::Infeasibility& certificate) {
  // The body that carries most of the certificate's direction.
  const fe::FloatingBody* worst = nullptr;
  Real largest = -1.0;
  for (const fe::FloatingBody& body : model.floating.bodies) {
    const Real share = block_of(body, certificate.direction).norm();
    if (share > largest) {
      largest = share;
      worst = &body;
    }
  }
  FRICON_CHECK(worst != nullptr, "refuse_unbalanced_load: no floating body");
  const fe::MotionCoefficients c = worst->motions * block_of(*worst, certificate.direction);
  const mesh::BoundingBox box =
      mesh::bounding_box(model.mesh, model.bodies.nodes[static_cast<size_t>(worst->body)]);
  const Real reach = 0.5 * (box.hi - box.lo).norm();  // [m]
  const Vec3 t = c.head<3>(), w = c.tail<3>();
  const bool force = t.norm() >= kTranslationShare * w.norm() * reach;
  const Real unit = force ? t.norm() : w.norm();
  const Real applied = certificate.applied / unit, carried = certificate.carried / unit;
  // A rotation with a translation t turns about the axis along w through c + w x t / |w|^2 (plus
  // a slide along w): the point to name.
  const Vec3 axis_point =
      force ? worst->centre : Vec3(worst->centre + w.cross(t) / w.squaredNorm());
  const std::string what =
      force ? fmt::format(
                  "the applied force along {} is {:.4g} N, but contact{} can carry at "
                  "most {:.4g} N along it",
                  vector_text(t / unit), applied, carried > 0.0 ? " and friction" : "", carried)
            : fmt::format(
                  "the applied moment about the axis {} through {} m is {:.4g} N m, but "
                  "contact{} can carry at most {:.4g} N m about it",
                  vector_text(w / unit), vector_text(axis_point), applied,
                  carried > 0.0 ? " and friction" : "", carried);
  throw UnbalancedLoad(fmt::format(
      "{}: contact: {} floats (its free motions: {}), and the load on it cannot be balanced by "
      "contact: {}; {}. Reduce the load, or hold the body by [[dirichlet]] conditions (theory.md "
      "§2.10)",
      problem.where("contact"), mesh::describe_body(model.mesh, model.bodies, worst->body),
      [&] {
        std::string s;
        for (Index j = 0; j < worst->n_motions(); ++j)
          s += fmt::format("{}{}", j == 0 ? "" : ", ", worst->motion_name(j));
        return s;
      }(),
      what,
      force ? "a pull away from the obstacle, or a push along it beyond the friction limit, "
              "moves the body without bound"
            : "a twist beyond what friction resists, or a tilt beyond what the pressure can "
              "balance, turns the body without bound"));
}

}  // namespace fricon::driver
