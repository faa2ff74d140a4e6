#pragma once
// Shared by the QP benchmarks (qp_variants_bench, expansion_bench, siconos_compare): the paper's
// brick (or any problem) built through the library exactly as `fricon solve` builds it (contact
// discretization, factor of K, the forward dual operator), with the dual problem of its first
// outer iteration (phi = 0).
#include <memory>
#include <utility>

#include "fricon/contact/discretization.hpp"
#include "fricon/contact/friction_law.hpp"
#include "fricon/contact/radii.hpp"
#include "fricon/driver/model.hpp"
#include "fricon/driver/paper.hpp"
#include "fricon/dual/dual_operator.hpp"

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
  d->law = contact::make_friction_law(d->problem.contact->friction);
  d->radius = contact::patch_radii(d->model.mesh, d->disc.surface, d->disc.patches, *d->law,
                                   VectorXd::Zero(d->disc.surface.n_nodes()), d->disc.slip_bound);
  return d;
}

/// The paper's brick for mesh parameter n, param = 6e4, at its first outer iteration.
inline std::unique_ptr<PaperDual> paper_dual(Index n) {
  return problem_dual(driver::paper_problem(n, 6e4));
}

}  // namespace fricon::bench
