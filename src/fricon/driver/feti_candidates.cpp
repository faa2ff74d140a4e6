// driver: the contact search's operators under Total FETI (driver/candidate_operators.hpp,
// theory.md §8.7): the subdomains are factored once, without contact rows; u0 is the
// displacement of the load held by the gluing and Dirichlet rows alone (solve_gluing), and each
// set of candidates puts its contact rows into the same operator (set_contact_rows), so that no
// subdomain is factored again.
#include <utility>

#include "fricon/driver/candidate_operators.hpp"
#include "fricon/driver/run_steps.hpp"
#include "fricon/driver/tfeti_solve.hpp"

namespace fricon::driver {

namespace {

class FetiCandidates final : public CandidateOperators {
 public:
  FetiCandidates(const Problem& problem, const Model& m, const RunOptions& options,
                 RunReport& report)
      : problem_(problem), options_(options), report_(report), n_free_(m.dofs.n_free()) {
    phase_start(options, "factorize");
    F_ = make_feti_operator(problem, m, nullptr, options, report);
  }

  const VectorXd& free_displacement() override {
    if (u0_.size() == 0) {
      phase_start(options_, "dual");
      ScopedPhase phase(report_.times, "dual");
      const long before = F_->n_products();
      // The load held by the gluing and Dirichlet rows alone (rows a call without the search
      // put in are taken out; the next call puts its own).
      if (F_->n_contact() > 0) F_->set_contact_rows(SparseMatrix(0, n_free_), VectorXd());
      u0_ = gluing_free_displacement(*F_, problem_, options_, report_);
      products_ = F_->n_products() - before;  // not yet reported
    }
    return u0_;
  }

  long take_free_displacement_solves() override { return std::exchange(products_, 0); }

  const dual::DualOperator& on_candidates(const contact::ContactDiscretization& part) override {
    phase_start(options_, "dual");
    ScopedPhase phase(report_.times, "dual");
    F_->set_contact_rows(part.B, part.offset);
    return *F_;
  }

  void record(RunReport& report) const override { record_feti_counts(*F_, report); }

 private:
  const Problem& problem_;
  const RunOptions& options_;
  RunReport& report_;
  const Index n_free_;  ///< the model's free dofs: the columns of a set of contact rows
  std::unique_ptr<feti::FetiOperator> F_;
  VectorXd u0_;
  long products_ = 0;
};

}  // namespace

std::unique_ptr<CandidateOperators> make_feti_candidates(const Problem& problem, const Model& m,
                                                         const RunOptions& options,
                                                         RunReport& report) {
  return std::make_unique<FetiCandidates>(problem, m, options, report);
}

}  // namespace fricon::driver
