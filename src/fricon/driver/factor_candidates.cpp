// driver: the contact search's operators on one factor of K (driver/candidate_operators.hpp):
// u0 = K^-1 f, one solve, and for each set of candidates a dual operator of its rows, made on the
// same factor with that u0 (theory.md §2.7).
#include <utility>

#include "fricon/driver/candidate_operators.hpp"
#include "fricon/driver/run_steps.hpp"

namespace fricon::driver {

namespace {

class FactorCandidates final : public CandidateOperators {
 public:
  FactorCandidates(const Problem& problem, const Model& m, const RunOptions& options,
                   RunReport& report)
      : problem_(problem), m_(m), options_(options), report_(report) {}

  const VectorXd& free_displacement() override {
    if (u0_.size() == 0) {
      ScopedPhase phase(report_.times, "dual");
      u0_ = m_.factor.solve(m_.f);
      solves_ = 1;
    }
    return u0_;
  }

  long take_free_displacement_solves() override { return std::exchange(solves_, 0); }

  const dual::DualOperator& on_candidates(const contact::ContactDiscretization& part) override {
    const VectorXd& u0 = free_displacement();
    phase_start(options_, "dual");
    ScopedPhase phase(report_.times, "dual");
    Q_.reset();  // one operator at a time
    dual::DualInput input{m_.factor,    part.B, m_.f, part.dofs, interrupt_poll(options_),
                          &part.offset, &u0};
    input.R = &m_.floating.R;
    Q_ = dual::make_dual_operator(problem_.solver.dual_operator, input);
    return *Q_;
  }

 private:
  const Problem& problem_;
  const Model& m_;
  const RunOptions& options_;
  RunReport& report_;
  VectorXd u0_;
  long solves_ = 0;  ///< of u0, not yet reported
  std::unique_ptr<dual::DualOperator> Q_;
};

}  // namespace

std::unique_ptr<CandidateOperators> make_factor_candidates(const Problem& problem, const Model& m,
                                                           const RunOptions& options,
                                                           RunReport& report) {
  return std::make_unique<FactorCandidates>(problem, m, options, report);
}

}  // namespace fricon::driver
