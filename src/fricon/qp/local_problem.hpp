#pragma once
// qp: a frictional contact problem in local form, as other codes write it (FCLIB's "local"
// problem, theory.md §5.6): find r and u = W r + q with, per contact (normal first, then two
// tangential components),
//   Coulomb  r in K_mu = {||r_t|| <= mu r_n},  u + mu ||u_t|| e_n in K_mu*,  r . (u + ...) = 0;
//   Tresca   r_n >= 0 complementary to u_n >= 0, ||r_t|| <= threshold with u_t opposite to r_t.
// In fricon's dual form W = Q, q = -h, r = lambda and u = g = Q lambda - h.

#include <optional>
#include <string>

#include "fricon/core/types.hpp"

namespace fricon::qp {

struct LocalProblem {
  SparseMatrix W;      ///< m x m, m = 3 n_contacts, symmetric positive (semi)definite
  VectorXd q;          ///< m
  VectorXd mu;         ///< n_contacts coefficients of friction (Coulomb), or empty
  VectorXd threshold;  ///< n_contacts slip thresholds (Tresca), or empty
  std::string source;  ///< where it came from (a file name)
  std::optional<VectorXd> reference_r;  ///< the file's own solution r, when it has one

  Index n_contacts() const { return q.size() / 3; }
  bool is_coulomb() const { return mu.size() > 0; }
};

}  // namespace fricon::qp
