#include "fricon/driver/paper.hpp"

#include <fmt/format.h>

namespace fricon::driver {

Problem paper_problem(Index n, Real param) {
  Problem p;
  p.source = fmt::format("paper(n = {}, param = {:g})", n, param);
  p.title = p.source;
  p.mesh.size = {3.0, 1.0, 1.0};
  p.mesh.cells = {3 * n, n, n};
  p.material.young = 21.19e10;
  p.material.poisson = 0.277;
  p.dirichlet.push_back({"x0", {true, true, true}});
  p.traction.push_back({"x1", Vec3(1.0e7, 0.0, 2.0e7)});
  p.traction.push_back({"z1", Vec3(0.0, 0.0, -3.0e7)});
  ContactOptions c;
  c.boundary = "z0";
  c.slip_bound = 2.0e7;
  c.friction.law = contact::FrictionLawKind::Paper;
  c.friction.param = param;
  p.contact = {c};
  p.solver.outer.tol = 1e-4;
  p.solver.qp.rel_tolerance = 1e-6;
  p.solver.qp.variant = qp::MpgpVariant::Paper;  // the paper's plain MPGP, so that n_mult compares
  p.solver.qp_expansion = qp::MpgpExpansion::Fixed;
  p.solver.qp.active_discs = qp::MpgpDiscFace::Held;
  p.output.dir = fmt::format("results/paper-n{}-param{:g}", n, param);
  return p;
}

const std::vector<PaperRow>& paper_table1() {
  static const std::vector<PaperRow> rows{
      {4, 6e4, 900, 36, 6, 2383, 13, 7.0e-6, 1.6e-5},
      {6, 6e4, 2646, 81, 6, 2063, 60, 1.6e-6, 4.6e-6},
      {8, 6e4, 5832, 144, 6, 3381, 341, 1.4e-6, 7.4e-6},
      {10, 6e4, 10890, 225, 6, 3622, 1006, 1.5e-6, 4.0e-6},
      {12, 6e4, 18252, 324, 6, 3985, 2565, 8.4e-7, 2.7e-6},
      {14, 6e4, 28350, 441, 7, 3962, 5221, 7.7e-7, 4.5e-6},
      {16, 6e4, 41616, 576, 6, 4432, 11033, 8.2e-7, 2.2e-6},
  };
  return rows;
}

const std::vector<PaperRow>& paper_table2() {
  static const std::vector<PaperRow> rows{
      {16, 2e4, 41616, 576, 6, 3870, 9705, 8.4e-7, 2.3e-6},
      {16, 6e4, 41616, 576, 6, 4432, 11033, 8.2e-7, 2.2e-6},
      {16, 3e5, 41616, 576, 7, 4604, 11490, 8.0e-7, 2.2e-6},
  };
  return rows;
}

}  // namespace fricon::driver
