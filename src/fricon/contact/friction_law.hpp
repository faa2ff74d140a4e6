#pragma once
// contact: coefficients of friction F(t) as functions of the tangential slip t = ||u_t|| [m].
// A law is a small interface: its value, the points where it is not smooth (so that integrals
// of F(phi_h) can be split there and computed exactly), and its Lipschitz constant (which governs
// the contraction of the successive approximations).

#include <memory>
#include <string>
#include <vector>

#include "fricon/core/types.hpp"

namespace fricon::contact {

class FrictionLaw {
 public:
  virtual ~FrictionLaw() = default;
  /// F(t) for a slip t >= 0 [m]; dimensionless, >= 0.
  virtual Real operator()(Real t) const = 0;
  /// Slips [m] where F is not smooth, increasing. Between two of them F is linear for the
  /// built-in laws.
  virtual std::vector<Real> kinks() const = 0;
  /// Lipschitz constant of F [1/m].
  virtual Real lipschitz() const = 0;
  /// Readable description, e.g. "paper(param = 60000)".
  virtual std::string describe() const = 0;
};

/// The paper's law (method.md §2.1): 0.3 up to t0 = 1e-5 m, then decreasing linearly with slope
/// 0.05 param to 0.2, reached at t0 + 2/param; `param` [1/m] > 0.
std::unique_ptr<FrictionLaw> paper_law(Real param);

/// A constant coefficient F(t) = value >= 0 (classical Tresca friction).
std::unique_ptr<FrictionLaw> constant_law(Real value);

/// Piecewise linear through (t_i, f_i), constant beyond the first and last points. `t` strictly
/// increasing, >= 0; `f` >= 0; equal sizes >= 1. Throws InputError otherwise.
std::unique_ptr<FrictionLaw> table_law(std::vector<Real> t, std::vector<Real> f);

}  // namespace fricon::contact
