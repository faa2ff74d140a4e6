#pragma once
// Shared by the QP benchmarks (qp_variants_bench, expansion_bench, siconos_compare): the paper's
// brick (or any problem) built through the library exactly as `fricon solve` builds it (contact
// discretization, factor of K, the forward dual operator), with the dual problem of its first
// outer iteration (phi = 0); and what they measure dense dual QPs with.
#include <algorithm>
#include <memory>
#include <utility>
#include <vector>

#include "fricon/contact/discretization.hpp"
#include "fricon/contact/friction_law.hpp"
#include "fricon/contact/radii.hpp"
#include "fricon/driver/model.hpp"
#include "fricon/driver/paper.hpp"
#include "fricon/dual/dual_operator.hpp"
#include "fricon/linalg/blas.hpp"
#include "fricon/qp/kkt.hpp"
#include "fricon/qp/mpgp.hpp"

namespace fricon::bench {

struct PaperDual {
  driver::Problem problem;
  driver::Model model;
  contact::ContactDiscretization disc;
  std::unique_ptr<contact::FrictionLaw> law;
  std::unique_ptr<dual::DualOperator> Q;  ///< forward: Q = B K^-1 B^T formed
  VectorXd radius;                        ///< disc radii at phi = 0 [Pa]
};

/// Any problem with a [contact] section, built as `fricon solve` builds it, at its first outer
/// iteration.
inline std::unique_ptr<PaperDual> problem_dual(driver::Problem problem) {
  auto d = std::make_unique<PaperDual>();
  d->problem = std::move(problem);
  PhaseTimes times;
  d->model = driver::assemble_model(d->problem, times);
  d->disc = driver::discretize_contact(d->problem, d->model.mesh, d->model.dofs);
  driver::factorize_model(d->model, {}, times);
  d->Q = dual::make_dual_operator(
      dual::DualOperatorKind::Forward,
      {d->model.factor, d->disc.B, d->model.f, d->disc.dofs, {}, &d->disc.offset});
  d->law = contact::make_friction_law(d->problem.contact.front().friction);
  d->radius = contact::patch_radii(d->model.mesh, d->disc.surface, d->disc.patches, *d->law,
                                   VectorXd::Zero(d->disc.surface.n_nodes()), d->disc.slip_bound);
  return d;
}

/// The paper's brick for mesh parameter n, param = 6e4, at its first outer iteration.
inline std::unique_ptr<PaperDual> paper_dual(Index n) {
  return problem_dual(driver::paper_problem(n, 6e4));
}

/// y = Q x with a dense symmetric Q, as the driver applies one (BLAS dsymv); refers to Q, which
/// must outlive the operator.
inline qp::Operator dense_operator(const MatrixXd& Q) {
  return [&Q](const VectorXd& x, VectorXd& y) { linalg::symmetric_product(Q, x, y); };
}

/// The constraints of a dual QP: per patch lambda_n >= 0 and ||lambda_t|| <= radius(p).
inline qp::SeparableConstraints disc_constraints(const VectorXd& radius) {
  auto c = qp::SeparableConstraints::contact_layout(radius.size());
  c.set_disc_radii(radius);
  return c;
}

/// The largest relative KKT residual of l for min 1/2 l^T Q l - l^T h over c
/// (qp::kkt_residuals with the default scales, g = Q l - h computed again).
inline double kkt_max(const MatrixXd& Q, const VectorXd& h, const qp::SeparableConstraints& c,
                      const VectorXd& l) {
  const VectorXd g = Q * l - h;
  const auto scales = qp::default_kkt_scales(l, h, c);
  return qp::kkt_residuals(l, g, c, scales.x, scales.g).max();
}

/// The median of `v` (of an even count, the upper of the middle two), not empty.
inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace fricon::bench
