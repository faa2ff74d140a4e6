#pragma once
// contact: coefficients of friction F(t) as functions of the tangential slip t = ||u_t|| [m].
// A law is a small interface: its value, the points where it is not smooth (so that integrals
// of F(phi_h) can be split there and computed exactly), and its Lipschitz constant (which governs
// the contraction of the successive approximations).

#include <array>
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "fricon/core/enum_names.hpp"
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
  /// F at many slips at once: out[i] = F(t[i]) (same sizes). Laws whose evaluation has a fixed
  /// cost per call (a Python function) override it; the default calls operator() per point.
  virtual void evaluate(std::span<const Real> t, std::span<Real> out) const;
  /// Whether F is linear between consecutive kinks (then the radii are integrated exactly);
  /// otherwise they are integrated by adaptive quadrature to quadrature_rtol().
  virtual bool piecewise_linear() const { return true; }
  /// Relative accuracy of the radii's quadrature for a law that is not piecewise linear.
  virtual Real quadrature_rtol() const { return 0.0; }
};

/// Which law: the paper's, a constant, a table, a formula, or a function given by code (the
/// [contact.friction] law key).
enum class FrictionLawKind { Paper, Constant, Table, Expression, Function };

/// A coefficient of friction given by code (e.g. a Python callable): fills out[i] = F(t[i]) for
/// slips t[i] >= 0 [m]; same sizes. May throw; the values are checked (finite, >= 0) by the law.
using FrictionFunction = std::function<void(std::span<const Real> t, std::span<Real> out)>;

/// Default relative accuracy of the quadrature of the radii for laws that are not piecewise
/// linear ([contact.friction] quadrature_rtol).
inline constexpr Real kDefaultQuadratureRtol = 1.0e-10;

/// A friction law as the user describes it ([contact.friction]); only the parameters of the
/// chosen kind are used (friction_law_parameters lists them).
struct FrictionLawSpec {
  FrictionLawKind law = FrictionLawKind::Paper;  ///< [law]
  Real param = 6.0e4;   ///< [param] paper's law (theory.md §7): slope parameter [1/m], > 0
  Real value = 0.3;     ///< [value] constant law: F, >= 0
  std::vector<Real> t;  ///< [t] table law: slips [m], strictly increasing, >= 0
  std::vector<Real> f;  ///< [f] table law: F at those slips, >= 0, as many as t
  /// [expression] expression law: a formula in the slip t [m] (muparser syntax), e.g.
  /// "0.1 + 0.4*exp(-t/5e-5)"; checked when the file is read.
  std::string expression;
  /// The function law's F, given by code (not by a problem file; the Python module).
  FrictionFunction function;
  /// A name for the function law in reports (e.g. the Python callable's name).
  std::string function_name = "function";
  /// [kinks] expression and function laws: slips [m] where F is not smooth, increasing, >= 0;
  /// the quadrature of the radii splits there.
  std::vector<Real> kinks;
  /// [quadrature_rtol] expression and function laws: relative accuracy of the radii, in (0, 1).
  Real quadrature_rtol = kDefaultQuadratureRtol;
};

/// The keys of [contact.friction] that law `kind` takes ({"param"}, {"value"}, {"t", "f"},
/// {"expression", "kinks", "quadrature_rtol"}, {"kinks", "quadrature_rtol"}).
std::span<const std::string_view> friction_law_parameters(FrictionLawKind kind);

/// The law a spec describes. Throws InputError for parameters out of range.
std::unique_ptr<FrictionLaw> make_friction_law(const FrictionLawSpec& spec);

/// The paper's law (theory.md §7): 0.3 up to t0 = 1e-5 m, then decreasing linearly with slope
/// 0.05 param to 0.2, reached at t0 + 2/param; `param` [1/m] > 0.
std::unique_ptr<FrictionLaw> paper_law(Real param);

/// What is wrong with a friction expression (check_friction_expression).
struct ExpressionProblem {
  /// 0-based offset in the expression where muparser found the problem; -1 when it names none
  /// (an empty expression).
  std::ptrdiff_t position = -1;
  std::string what;    ///< "syntax error" or "unknown name \"x\""
  std::string detail;  ///< muparser's message without its position, or a hint
};

/// Parses a friction expression (muparser syntax, the only variable t [m]) once, without
/// evaluating it for any meaningful slip. Returns nothing when it is valid.
std::optional<ExpressionProblem> check_friction_expression(const std::string& expression);

/// F given by a formula in t (spec.expression; muparser). Throws InputError for an invalid
/// expression, kinks that are not increasing and >= 0, or quadrature_rtol outside (0, 1). Each
/// law object owns one parser guarded by a mutex: evaluating from several threads is safe but
/// serialized. Every value computed is checked (finite, >= 0; InputError naming the slip).
std::unique_ptr<FrictionLaw> expression_law(const FrictionLawSpec& spec);

/// F given by code (spec.function, a batch function; spec.function_name in describe()). Each
/// evaluate() calls it once for the whole batch, operator() once with one slip; every value it
/// returns is checked (finite, >= 0; InputError naming the slip). Throws InputError for an empty
/// function or bad kinks / quadrature_rtol.
std::unique_ptr<FrictionLaw> function_law(const FrictionLawSpec& spec);

/// A constant coefficient F(t) = value >= 0 (classical Tresca friction).
std::unique_ptr<FrictionLaw> constant_law(Real value);

/// Piecewise linear through (t_i, f_i), constant beyond the first and last points. `t` strictly
/// increasing, >= 0; `f` >= 0; equal sizes >= 1. Throws InputError otherwise.
std::unique_ptr<FrictionLaw> table_law(std::vector<Real> t, std::vector<Real> f);

}  // namespace fricon::contact

FRICON_ENUM_NAMES(fricon::contact::FrictionLawKind, "contact.friction.law",
                  {contact::FrictionLawKind::Paper, "paper"},
                  {contact::FrictionLawKind::Constant, "constant"},
                  {contact::FrictionLawKind::Table, "table"},
                  {contact::FrictionLawKind::Expression, "expression"},
                  {contact::FrictionLawKind::Function, "function"});
