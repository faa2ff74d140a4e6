#pragma once
// qp: a diagonal change of variables of the QP (docs/theory.md §4.5),
//
//   x = D y,  D = diag(d), d > 0 and equal on the unknowns of one block,
//
// so that min 1/2 x^T A x - b^T x over Omega becomes min 1/2 y^T (D A D) y - (D b)^T y over
// D^-1 Omega: a bound stays the bound y_i >= 0, a Free unknown stays free and a disc of radius rho
// becomes the disc of radius rho / d_i. The gradient of the scaled problem is D g. MPGP's rate
// depends on the condition number of the matrix it sees; with one factor per contact patch, chosen
// so that every patch's diagonal block of D A D is about 1, the patches of a graded mesh (areas a
// hundred times apart) no longer spread the spectrum. x and its solution are the same points: only
// the iteration and the meaning of its relative tolerance change.

#include <Eigen/Core>

#include "fricon/qp/constraints.hpp"
#include "fricon/qp/kkt.hpp"
#include "fricon/qp/mpgp.hpp"
#include "fricon/qp/operator.hpp"
#include "fricon/qp/smalse.hpp"

namespace fricon::qp {

class BlockScaling {
 public:
  /// The identity (no scaling) for n unknowns.
  static BlockScaling identity(Index n);
  /// One factor per block of c (in the order of c.blocks), each > 0 and finite. Throws InputError
  /// otherwise or when the sizes do not match.
  static BlockScaling per_block(const SeparableConstraints& c, const Eigen::VectorXd& factor);

  /// d per unknown.
  const Eigen::VectorXd& d() const { return d_; }
  Index size() const { return d_.size(); }

  /// y = D^-1 x.
  Eigen::VectorXd to_scaled(const Eigen::VectorXd& x) const { return x.cwiseQuotient(d_); }
  /// x = D y.
  Eigen::VectorXd from_scaled(const Eigen::VectorXd& y) const { return y.cwiseProduct(d_); }
  /// D v: the scaled image of a gradient or of b.
  Eigen::VectorXd dual_to_scaled(const Eigen::VectorXd& v) const { return v.cwiseProduct(d_); }
  /// y -> D A D y.
  Operator scaled(const Operator& A) const;
  /// y -> D^-1 M D^-1 y: the image of M, an approximation of A^-1 (a preconditioner), under the
  /// change of variables, an approximation of (D A D)^-1.
  Operator scaled_inverse(const Operator& M) const;
  /// The options `opt` with their preconditioner, if any, made scaled_inverse of it.
  MpgpOptions scaled(const MpgpOptions& opt) const;
  /// D^-1 Omega: the same blocks, each disc radius divided by its block's factor.
  SeparableConstraints scaled(const SeparableConstraints& c) const;

 private:
  explicit BlockScaling(Eigen::VectorXd d) : d_(std::move(d)) {}
  Eigen::VectorXd d_;
};

/// solve_mpgp on the scaled problem: x (in, the initial guess; out, the last iterate) stays in
/// the original variables; opt.norm_A must be ||D A D|| (or 0: estimated on D A D), and
/// opt.preconditioner, if any, approximates A^-1 (it is scaled with A); the report's norms
/// (gradients, b, the reference of the stopping test) are those of the scaled problem.
MpgpReport solve_mpgp_scaled(const Operator& A, const Eigen::VectorXd& b,
                             const SeparableConstraints& c, const BlockScaling& D,
                             const MpgpOptions& opt, Eigen::VectorXd& x);

/// solve_smalse (qp/smalse.hpp) on the scaled problem, as solve_mpgp_scaled: G becomes G D;
/// x and mu stay in the original variables (mu is the same in both).
SmalseReport solve_smalse_scaled(const Operator& A, const Eigen::VectorXd& b,
                                 const SeparableConstraints& c, const BlockScaling& D,
                                 const EqualityConstraint& eq, const SmalseOptions& opt,
                                 const MpgpOptions& inner, Eigen::VectorXd& x, Eigen::VectorXd& mu);

/// The KKT residuals (kkt.hpp) of x with gradient g = A x - b, measured in the scaled problem
/// and relative to its stopping test's reference: scale_x = max(||D^-1 x||_inf, largest scaled
/// radius), scale_g = ||D b_R|| (or ||D b|| for StopReference::Whole), a zero scale replaced by
/// 1. A QP stopped by solve_mpgp_scaled at rel_tolerance has residuals of that order.
/// data_scale > 0 replaces ||D b_R||: x is part of a larger QP (Total FETI's contact multipliers
/// among the equality ones) whose stopping test referred to the whole of its data.
KktResiduals scaled_kkt_residuals(const Eigen::VectorXd& x, const Eigen::VectorXd& g,
                                  const Eigen::VectorXd& b, const SeparableConstraints& c,
                                  const BlockScaling& D, StopReference reference,
                                  double data_scale = 0.0);

}  // namespace fricon::qp
