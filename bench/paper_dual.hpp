#pragma once
// Shared by the QP benchmarks (qp_variants_bench, siconos_compare): the dual problem of the first
// outer iteration (phi = 0) of the paper's brick, built through the library as the driver builds
// it (Q by the forward sweep over the reach of the contact surface), with everything the outer
// loop needs besides; and the parsing of comma-separated option values.
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "fricon/contact/contact_surface.hpp"
#include "fricon/contact/friction_law.hpp"
#include "fricon/core/error.hpp"
#include "fricon/driver/model.hpp"
#include "fricon/driver/paper.hpp"

namespace fricon::bench {

struct PaperDual {
  driver::Problem problem;
  driver::Model model;
  contact::ContactSurface surface;
  contact::Patches patches;
  SparseMatrix B;
  std::unique_ptr<contact::FrictionLaw> law;
  VectorXd slip_bound;  ///< g per surface node [Pa]
  MatrixXd Q;           ///< B K^-1 B^T
  VectorXd h;           ///< B K^-1 f
  VectorXd radius;      ///< disc radii at phi = 0 [Pa]
};

/// The paper's brick for mesh parameter n, param = 6e4, at its first outer iteration.
inline std::unique_ptr<PaperDual> paper_dual(Index n) {
  auto d = std::make_unique<PaperDual>();
  d->problem = driver::paper_problem(n, 6e4);
  PhaseTimes times;
  d->model = driver::build_model(d->problem, times);
  const driver::Model& m = d->model;
  const auto& opt = *d->problem.contact;
  d->surface = contact::make_contact_surface(m.mesh, m.dofs, opt.boundary, d->problem.source);
  d->patches = contact::chessboard_patches(m.mesh, d->surface, d->problem.source);
  d->B = contact::assemble_b(m.mesh, m.dofs, d->surface, d->patches);
  d->law = contact::paper_law(opt.friction.param);
  d->slip_bound = VectorXd::Constant(d->surface.n_nodes(), opt.slip_bound);
  d->radius = contact::patch_radii(m.mesh, d->surface, d->patches, *d->law,
                                   VectorXd::Zero(d->surface.n_nodes()), d->slip_bound);
  d->h = d->B * m.factor.solve(VectorXd(m.f));
  d->Q = m.factor.inverse_gram(SparseMatrix(d->B.transpose()));
  return d;
}

/// "a,b,c" -> {convert("a"), convert("b"), convert("c")}; throws InputError on an empty list.
template <typename T, typename F>
std::vector<T> parse_list(const std::string& s, F convert) {
  std::vector<T> out;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, ',');)
    if (!item.empty()) out.push_back(convert(item));
  if (out.empty()) throw InputError(fmt::format("empty list '{}'", s));
  return out;
}

}  // namespace fricon::bench
