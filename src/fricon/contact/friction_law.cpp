#include "fricon/contact/friction_law.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>

#include <fmt/format.h>
#include <muParser.h>

#include "fricon/core/error.hpp"

namespace fricon::contact {

namespace {

// Piecewise linear through points, constant outside; all built-in laws are of this kind.
class PiecewiseLinear : public FrictionLaw {
 public:
  PiecewiseLinear(std::vector<Real> t, std::vector<Real> f, std::string description)
      : t_(std::move(t)), f_(std::move(f)), description_(std::move(description)) {}

  Real operator()(Real s) const override {
    if (s <= t_.front()) return f_.front();
    if (s >= t_.back()) return f_.back();
    const size_t k = static_cast<size_t>(std::upper_bound(t_.begin(), t_.end(), s) - t_.begin());
    const Real w = (s - t_[k - 1]) / (t_[k] - t_[k - 1]);
    return (1.0 - w) * f_[k - 1] + w * f_[k];
  }
  std::vector<Real> kinks() const override { return t_; }
  Real lipschitz() const override {
    Real L = 0.0;
    for (size_t k = 1; k < t_.size(); ++k)
      L = std::max(L, std::abs(f_[k] - f_[k - 1]) / (t_[k] - t_[k - 1]));
    return L;
  }
  std::string describe() const override { return description_; }

 private:
  std::vector<Real> t_, f_;
  std::string description_;
};

// Start of the paper's transition [m] (theory.md §7).
constexpr Real kPaperT0 = 1e-5;

// The name of the slip variable in friction expressions.
constexpr const char* kSlipVariable = "t";

// Throws InputError unless F(t) = value is a coefficient of friction (finite, >= 0). `who`
// starts the message: "contact.friction.expression: " or "contact.friction: the function law's ".
void check_coefficient(std::string_view who, Real t, Real value) {
  if (std::isfinite(value) && value >= 0.0) return;
  throw InputError(
      fmt::format("{}F(t = {:.6g} m) = {:.6g}: a coefficient of friction must be finite and >= 0",
                  who, t, value));
}

// The kinks and the quadrature tolerance of the expression and function laws.
void check_quadrature_keys(const FrictionLawSpec& spec) {
  for (size_t k = 0; k < spec.kinks.size(); ++k)
    if (!(spec.kinks[k] >= 0.0) || !std::isfinite(spec.kinks[k]) ||
        (k > 0 && !(spec.kinks[k] > spec.kinks[k - 1])))
      throw InputError(
          fmt::format("contact.friction.kinks[{}] = {}: kinks must be >= 0 and strictly increasing",
                      k, spec.kinks[k]));
  if (!(spec.quadrature_rtol > 0.0 && spec.quadrature_rtol < 1.0))
    throw InputError(
        fmt::format("contact.friction.quadrature_rtol = {}: expected a number in "
                    "(0, 1)",
                    spec.quadrature_rtol));
}

// muparser's message without its trailing " at position N" / " found at position N." (the
// position is reported as a column by the caller).
std::string without_position(std::string msg) {
  for (const char* tail : {" found at position", " at position"}) {
    const auto at = msg.find(tail);
    if (at != std::string::npos) return msg.substr(0, at);
  }
  while (!msg.empty() && msg.back() == '.')
    msg.pop_back();
  return msg;
}

// A parser of `expression` with the slip variable bound to *t.
void setup_parser(mu::Parser& parser, const std::string& expression, double* t) {
  parser.DefineVar(kSlipVariable, t);
  parser.SetExpr(expression);
}

// Common part of the laws that are not piecewise linear.
class QuadratureLaw : public FrictionLaw {
 public:
  explicit QuadratureLaw(const FrictionLawSpec& spec)
      : kinks_(spec.kinks), rtol_(spec.quadrature_rtol) {}
  std::vector<Real> kinks() const override { return kinks_; }
  /// Not known for a general F: NaN (tresca_map's stall hint says so).
  Real lipschitz() const override { return std::numeric_limits<Real>::quiet_NaN(); }
  bool piecewise_linear() const override { return false; }
  Real quadrature_rtol() const override { return rtol_; }
  /// One point through evaluate(), which every such law implements (and checks).
  Real operator()(Real t) const final {
    Real v = 0.0;
    evaluate(std::span<const Real>(&t, 1), std::span<Real>(&v, 1));
    return v;
  }

 private:
  std::vector<Real> kinks_;
  Real rtol_;
};

// F by a muparser formula. One parser per law; a mutex makes each evaluation exclusive (the
// parser reads the slip from the member variable t_).
class ExpressionLaw final : public QuadratureLaw {
 public:
  explicit ExpressionLaw(const FrictionLawSpec& spec)
      : QuadratureLaw(spec), expression_(spec.expression) {
    if (const auto problem = check_friction_expression(expression_))
      throw InputError(fmt::format(
          "contact.friction.expression: {} at column {} of \"{}\": {}", problem->what,
          std::max<std::ptrdiff_t>(problem->position, 0) + 1, expression_, problem->detail));
    setup_parser(parser_, expression_, &t_);
  }

  void evaluate(std::span<const Real> t, std::span<Real> out) const override {
    FRICON_CHECK(t.size() == out.size(),
                 "evaluate: " << t.size() << " slips, " << out.size() << " values");
    const std::lock_guard<std::mutex> lock(mutex_);
    for (size_t i = 0; i < t.size(); ++i) {
      t_ = t[i];
      try {
        out[i] = parser_.Eval();
      } catch (const mu::Parser::exception_type& e) {
        throw InputError(fmt::format("contact.friction.expression: F(t = {} m): {}", t[i],
                                     without_position(e.GetMsg())));
      }
      check_coefficient("contact.friction.expression: ", t[i], out[i]);
    }
  }

  std::string describe() const override { return fmt::format("expression(\"{}\")", expression_); }

 private:
  std::string expression_;
  mutable std::mutex mutex_;
  mutable double t_ = 0.0;
  mutable mu::Parser parser_;
};

// F by a function given from code, called once per batch.
class FunctionLaw final : public QuadratureLaw {
 public:
  explicit FunctionLaw(const FrictionLawSpec& spec)
      : QuadratureLaw(spec), function_(spec.function), name_(spec.function_name) {}

  // `out` is filled with NaN first: a value the function does not set is reported as F = nan.
  void evaluate(std::span<const Real> t, std::span<Real> out) const override {
    FRICON_CHECK(t.size() == out.size(),
                 "evaluate: " << t.size() << " slips, " << out.size() << " values");
    std::fill(out.begin(), out.end(), std::numeric_limits<Real>::quiet_NaN());
    function_(t, out);
    for (size_t i = 0; i < t.size(); ++i)
      check_coefficient("contact.friction: the function law's ", t[i], out[i]);
  }

  std::string describe() const override { return fmt::format("function({})", name_); }

 private:
  FrictionFunction function_;
  std::string name_;
};

}  // namespace

void FrictionLaw::evaluate(std::span<const Real> t, std::span<Real> out) const {
  FRICON_CHECK(t.size() == out.size(),
               "evaluate: " << t.size() << " slips, " << out.size() << " values");
  for (size_t i = 0; i < t.size(); ++i)
    out[i] = (*this)(t[i]);
}

std::optional<ExpressionProblem> check_friction_expression(const std::string& expression) {
  try {
    mu::Parser parser;
    double t = 0.0;
    setup_parser(parser, expression, &t);
    parser.Eval();  // muparser parses on the first evaluation; the value is not used
  } catch (const mu::Parser::exception_type& e) {
    ExpressionProblem p;
    p.position = e.GetPos();
    if (e.GetCode() == mu::ecUNASSIGNABLE_TOKEN) {
      p.what = fmt::format("unknown name \"{}\"", e.GetToken());
      p.detail = fmt::format(
          "the only variable is {}, the slip [m] (docs/problem-file.md lists "
          "the functions)",
          kSlipVariable);
    } else {
      p.what = "syntax error";
      p.detail = without_position(e.GetMsg());
    }
    return p;
  }
  return std::nullopt;
}

std::unique_ptr<FrictionLaw> expression_law(const FrictionLawSpec& spec) {
  check_quadrature_keys(spec);
  return std::make_unique<ExpressionLaw>(spec);
}

std::unique_ptr<FrictionLaw> function_law(const FrictionLawSpec& spec) {
  if (!spec.function)
    throw InputError("contact.friction: law \"function\" needs a function given from code");
  check_quadrature_keys(spec);
  return std::make_unique<FunctionLaw>(spec);
}

std::span<const std::string_view> friction_law_parameters(FrictionLawKind kind) {
  static constexpr std::array<std::string_view, 1> kPaper{"param"}, kConstant{"value"};
  static constexpr std::array<std::string_view, 2> kTable{"t", "f"},
      kFunction{"kinks", "quadrature_rtol"};
  static constexpr std::array<std::string_view, 3> kExpression{"expression", "kinks",
                                                               "quadrature_rtol"};
  switch (kind) {
    case FrictionLawKind::Paper:
      return kPaper;
    case FrictionLawKind::Constant:
      return kConstant;
    case FrictionLawKind::Table:
      return kTable;
    case FrictionLawKind::Expression:
      return kExpression;
    case FrictionLawKind::Function:
      return kFunction;
  }
  return {};
}

std::unique_ptr<FrictionLaw> make_friction_law(const FrictionLawSpec& spec) {
  switch (spec.law) {
    case FrictionLawKind::Paper:
      return paper_law(spec.param);
    case FrictionLawKind::Constant:
      return constant_law(spec.value);
    case FrictionLawKind::Table:
      return table_law(spec.t, spec.f);
    case FrictionLawKind::Expression:
      return expression_law(spec);
    case FrictionLawKind::Function:
      return function_law(spec);
  }
  throw InputError(
      fmt::format("contact.friction.law: invalid value {}", static_cast<int>(spec.law)));
}

std::unique_ptr<FrictionLaw> paper_law(Real param) {
  if (!(param > 0.0) || !std::isfinite(param))
    throw InputError(fmt::format("friction law 'paper': param = {} must be positive", param));
  return std::make_unique<PiecewiseLinear>(std::vector<Real>{kPaperT0, kPaperT0 + 2.0 / param},
                                           std::vector<Real>{0.3, 0.2},
                                           fmt::format("paper(param = {})", param));
}

std::unique_ptr<FrictionLaw> constant_law(Real value) {
  if (!(value >= 0.0) || !std::isfinite(value))
    throw InputError(fmt::format("friction law 'constant': value = {} must be >= 0", value));
  return std::make_unique<PiecewiseLinear>(std::vector<Real>{0.0}, std::vector<Real>{value},
                                           fmt::format("constant({})", value));
}

std::unique_ptr<FrictionLaw> table_law(std::vector<Real> t, std::vector<Real> f) {
  if (t.empty() || t.size() != f.size())
    throw InputError(
        fmt::format("friction law 'table': t and f need the same size >= 1 (got {} and {})",
                    t.size(), f.size()));
  for (size_t k = 0; k < t.size(); ++k) {
    if (!(t[k] >= 0.0) || !std::isfinite(t[k]) || (k > 0 && !(t[k] > t[k - 1])))
      throw InputError(fmt::format(
          "friction law 'table': t[{}] = {} (t must be >= 0 and strictly increasing)", k, t[k]));
    if (!(f[k] >= 0.0) || !std::isfinite(f[k]))
      throw InputError(fmt::format("friction law 'table': f[{}] = {} must be >= 0", k, f[k]));
  }
  const std::string d = fmt::format("table({} points)", t.size());
  return std::make_unique<PiecewiseLinear>(std::move(t), std::move(f), d);
}

}  // namespace fricon::contact
