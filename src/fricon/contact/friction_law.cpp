#include "fricon/contact/friction_law.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "fricon/core/error.hpp"

namespace fricon::contact {

void FrictionLaw::evaluate(std::span<const Real> t, std::span<Real> out) const {
  FRICON_CHECK(t.size() == out.size(), "FrictionLaw::evaluate: " << t.size() << " slips, "
                                                                  << out.size() << " values");
  for (std::size_t i = 0; i < t.size(); ++i)
    out[i] = (*this)(t[i]);
}

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

}  // namespace

std::span<const std::string_view> friction_law_parameters(FrictionLawKind kind) {
  static constexpr std::array<std::string_view, 1> kPaper{"param"}, kConstant{"value"};
  static constexpr std::array<std::string_view, 2> kTable{"t", "f"};
  switch (kind) {
    case FrictionLawKind::Paper:
      return kPaper;
    case FrictionLawKind::Constant:
      return kConstant;
    case FrictionLawKind::Table:
      return kTable;
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
