#pragma once
// driver: what the contact search (theory.md §2.7) asks of a backend: the displacement without
// contact it chooses the first candidates from, and a dual operator on the contact rows of each
// set of candidates. One implementation per backend and file:
//   factor_candidates.cpp  one factor of K: u0 = K^-1 f, and a dual operator made for each set
//   feti_candidates.cpp    Total FETI: u0 from the gluing alone, and one operator on the
//                          subdomains, factored once, whose contact rows each set replaces
//                          (theory.md §8.7)

#include <memory>

#include "fricon/contact/discretization.hpp"
#include "fricon/driver/model.hpp"
#include "fricon/driver/problem.hpp"
#include "fricon/driver/run.hpp"
#include "fricon/dual/dual_operator.hpp"

namespace fricon::driver {

class CandidateOperators {
 public:
  virtual ~CandidateOperators() = default;
  /// u0, the displacement of the load without contact over the model's free dofs [m]; solved at
  /// the first call (phase "dual"), kept for the next.
  virtual const VectorXd& free_displacement() = 0;
  /// Solves with K (or rounds of solves with every subdomain's factor) that free_displacement
  /// took, for the report's count: once, 0 after that (a search again on the same model, after
  /// a geometric update, reuses u0).
  virtual long take_free_displacement_solves() = 0;
  /// The dual operator of the contact rows of `part` (contact::restrict_to_patches of the
  /// problem's discretization), which must outlive it; valid until the next call (phase "dual").
  virtual const dual::DualOperator& on_candidates(const contact::ContactDiscretization& part) = 0;
  /// After the search's last solve: the backend's own counts into the report.
  virtual void record(RunReport& report) const { (void)report; }
};

/// The operators of the problem's backend (solver.backend) on model `m`, with its factor of K
/// (build_factored_model), or for "tfeti" its subdomains, factored here (phase "factorize",
/// report.feti). `m`, `problem` and `options` must outlive the result.
std::unique_ptr<CandidateOperators> make_candidate_operators(const Problem& problem, const Model& m,
                                                             const RunOptions& options,
                                                             RunReport& report);

/// The implementations (factor_candidates.cpp, feti_candidates.cpp).
std::unique_ptr<CandidateOperators> make_factor_candidates(const Problem& problem, const Model& m,
                                                           const RunOptions& options,
                                                           RunReport& report);
std::unique_ptr<CandidateOperators> make_feti_candidates(const Problem& problem, const Model& m,
                                                         const RunOptions& options,
                                                         RunReport& report);

}  // namespace fricon::driver
