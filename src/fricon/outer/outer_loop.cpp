#include "fricon/outer/outer_loop.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "fricon/core/error.hpp"
#include "fricon/core/timer.hpp"
#include "fricon/outer/anderson.hpp"

namespace fricon::outer {

void OuterOptions::validate() const {
  require("OuterOptions::tol", tol, kOuterTolRange);
  require("OuterOptions::max_iterations", max_iterations, kOuterMaxRange);
  if (!enum_is_valid(acceleration))
    throw InputError(fmt::format("OuterOptions::acceleration: expected {}, got {}",
                                 enum_choices<Acceleration>(), static_cast<int>(acceleration)));
  require("OuterOptions::anderson_depth", anderson_depth, kAndersonDepthRange);
  require("OuterOptions::stall_window", stall_window, integer_at_least(1));
}

Real relative_change(const VectorXd& now, const VectorXd& before, Real scale) {
  const Real reference = std::max(now.norm(), scale);
  if (reference > 0.0) return (now - before).norm() / reference;
  return before.norm() > 0.0 ? 1.0 : 0.0;
}

Real contraction_ratio(const std::vector<Real>& err) {
  const size_t n = err.size();
  if (n < 3) return 0.0;
  const size_t first = n >= 5 ? n - 4 : 1;  // the ratios of the last (up to) three steps
  if (!(err[first] > 0.0) || !(err.back() > 0.0)) return 0.0;
  return std::pow(err.back() / err[first], 1.0 / static_cast<Real>(n - 1 - first));
}

bool stalled(const std::vector<Real>& err, size_t window) {
  if (err.size() <= window + 1) return false;
  const auto split = err.end() - static_cast<std::ptrdiff_t>(window);
  return *std::min_element(split, err.end()) >= *std::min_element(err.begin(), split);
}

namespace {

std::string history_text(const std::vector<Real>& err) {
  std::string s;
  for (Real e : err)
    s += fmt::format(" {:.3e}", e);
  return s;
}

void check_layout(const std::vector<StateBlock>& blocks, const VectorXd& x) {
  Index total = 0;
  for (const auto& b : blocks)
    total += b.size;
  if (blocks.empty() || total != x.size())
    throw InputError(fmt::format(
        "outer loop: the state has {} entries but the map's blocks cover {}", x.size(), total));
}

// err(k) per block: the relative change from the state Psi started from to its image.
std::vector<Real> block_changes(const std::vector<StateBlock>& blocks, const VectorXd& image,
                                const VectorXd& x) {
  std::vector<Real> err;
  Index offset = 0;
  for (const auto& b : blocks) {
    err.push_back(
        relative_change(image.segment(offset, b.size), x.segment(offset, b.size), b.scale));
    offset += b.size;
  }
  return err;
}

// The reason to stop right after iteration k, if any, in the order: the inner solve's own
// failure or interruption, convergence, a stop request, a stall. A stop requested once the
// iteration's inner solve has ended does not undo its convergence: the iterate is the answer.
std::optional<std::pair<OuterTermination, std::string>> stop_reason(const MapStep& step,
                                                                    const std::atomic<bool>* stop,
                                                                    int k, const OuterReport& rep,
                                                                    const OuterOptions& options,
                                                                    const FixedPointMap& map) {
  const auto interrupted = [k] {
    return std::pair{OuterTermination::Interrupted,
                     fmt::format("interrupted during outer iteration {}", k)};
  };
  if (step.status == StepStatus::Interrupted) return interrupted();
  if (step.status == StepStatus::Failed) return std::pair{OuterTermination::QpFailed, step.message};
  const Real err = rep.err_history.back();
  if (err <= options.tol) return std::pair{OuterTermination::Converged, std::string()};
  if (stop != nullptr && stop->load()) return interrupted();
  // Psi contracts when the friction law's Lipschitz constant is small (theory.md §1.5); then
  // err(k) falls at every step. If it has not gone below its best value for stall_window
  // iterations (growth, or a cycle between states), the iteration does not contract.
  const auto window = static_cast<size_t>(options.stall_window);
  if (stalled(rep.err_history, window)) {
    const std::string hint = map.stall_hint();
    return std::pair{
        OuterTermination::Stalled,
        fmt::format("the successive approximations do not contract: err(k) has not gone below "
                    "its best value {:.3g} for {} iterations (observed ratio err(k)/err(k-1) = "
                    "{:.3g}){}; err(k):{}",
                    *std::min_element(rep.err_history.begin(), rep.err_history.end()), window,
                    contraction_ratio(rep.err_history), hint.empty() ? "" : "; " + hint,
                    history_text(rep.err_history))};
  }
  return std::nullopt;
}

}  // namespace

OuterReport iterate(FixedPointMap& map, VectorXd& x, const OuterOptions& options,
                    const std::function<void(const OuterIteration&)>& monitor,
                    const std::atomic<bool>* stop) {
  options.validate();
  const std::vector<StateBlock> blocks = map.layout();
  check_layout(blocks, x);
  AndersonMixing anderson(options.anderson_depth);
  OuterReport rep;
  VectorXd image = VectorXd::Zero(x.size());
  for (int k = 1; k <= options.max_iterations; ++k) {
    // @sect: one application of Psi and its relative change.
    const Stopwatch watch;
    const MapStep step = map.apply(k, x, image);
    OuterIteration it;
    it.k = k;
    it.block_err = block_changes(blocks, image, x);
    it.err = *std::max_element(it.block_err.begin(), it.block_err.end());
    it.seconds = watch.seconds();
    rep.iterations = k;
    rep.err_history.push_back(it.err);
    rep.block_history.push_back(it.block_err);
    rep.contraction_ratio = contraction_ratio(rep.err_history);
    rep.fixed_point_residual = it.err;
    if (monitor) monitor(it);

    // @sect: stop, or move to the next state.
    if (const auto reason = stop_reason(step, stop, k, rep, options, map)) {
      rep.termination = reason->first;
      rep.message = reason->second;
      return rep;
    }
    x = options.acceleration == Acceleration::Anderson ? anderson.next(x, image) : image;
  }
  rep.termination = OuterTermination::IterationLimit;
  rep.message = fmt::format(
      "the successive approximations did not reach err <= {:.1e} in {} iterations (observed "
      "contraction ratio {:.3g}); err(k):{}",
      options.tol, options.max_iterations, rep.contraction_ratio, history_text(rep.err_history));
  return rep;
}

}  // namespace fricon::outer
