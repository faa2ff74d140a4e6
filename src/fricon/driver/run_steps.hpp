#pragma once
// driver: the steps of a run that both backends share (run.cpp on one process, the distributed
// run of parallel/mpi/ on rank 0): the outer loop on a dual operator, and the postprocessing.

#include <functional>
#include <optional>
#include <string>

#include "fricon/driver/run.hpp"

namespace fricon::driver {

class CandidateOperators;

void phase_start(const RunOptions& options, const std::string& name);

/// The poll of a dual operator while it forms Q: throws Interrupted when a stop was requested.
std::function<void()> interrupt_poll(const RunOptions& options);

/// The outcome of a contact solve into the run's result (status, message, forces, the contact
/// report and fields); returns the displacement over the free dofs.
VectorXd adopt(ContactOutcome&& outcome, RunResult& r);

/// The elastic model of the problem (phases "mesh", "assembly"), with [contact] its contact
/// discretization (phase "contact"), and the factor of K ordered as the dual operator asks
/// (phase "factorize"), with the sizes and the factor's figures in r.report. Returns the
/// discretization (none without contact). The checks before the factorization are those of
/// check_model (driver/model.hpp), which `fricon check` runs too: a problem found then costs no
/// factorization.
std::optional<contact::ContactDiscretization> build_factored_model(const Problem& problem,
                                                                   const RunOptions& options,
                                                                   RunResult& r);

/// The outer loop of dual QPs on operator Q (phase "outer loop"); fills the contact part of
/// r.report and r.contact and returns the displacement over the free dofs.
VectorXd solve_with_operator(const Problem& problem, const contact::ContactDiscretization& disc,
                             const dual::DualOperator& Q, const RunOptions& options, RunResult& r);

/// After this many growths of the contact search's candidates, the next solve takes every patch.
inline constexpr int kMaxSearchRounds = 8;

/// The rounds of the contact search on one problem (theory.md §2.7): after each round the
/// left-out patches to add, and the counts of the rounds before the answer, which its report
/// includes.
class SearchRounds {
 public:
  /// `solves_before`: solves with K made before the first round (the static run's u0).
  explicit SearchRounds(long solves_before = 0) : solves_(solves_before) {}

  /// The patches to add (increasing, none of `candidates`) after round `round` (1-based), whose
  /// outcome c was solved on `candidates` (increasing patch indices of disc): those left out
  /// whose mean penetration exceeds `tolerance` [m], and after kMaxSearchRounds growths every
  /// left-out patch. Empty when c is the answer: none penetrates, a stop was requested, or
  /// the round failed otherwise than by its certificate.
  std::vector<Index> patches_to_add(const contact::ContactDiscretization& disc,
                                    const std::vector<Index>& candidates, const ContactOutcome& c,
                                    Real tolerance, int round, const RunOptions& options);
  /// The answer c, with the products with Q, QP steps and solves of the earlier rounds added,
  /// into r (adopt); returns the displacement over the free dofs.
  VectorXd adopt_answer(ContactOutcome&& c, RunResult& r) const;

 private:
  long products_ = 0, qp_iterations_ = 0, solves_ = 0;
  qp::MpgpSteps steps_;
};

/// Whether the contact search leaves patches out (theory.md §2.7): solver.contact_search is not
/// off, and no patch resists without pressure (Tresca with a positive slip bound). With a
/// floating body of `model` (theory.md §2.10) a static run starts the search from the closed
/// gaps; a loading path, whose search starts each step from a free displacement, solves every
/// patch. Under Total FETI the search starts from the gluing's displacement (theory.md §8.7),
/// and a floating body's static run solves every patch too.
bool search_applies(const Problem& problem, const Model& model);

/// Every patch of `disc`, 0 .. n_patches - 1.
std::vector<Index> all_patches(const contact::ContactDiscretization& disc);

/// The outer loop of dual QPs on the patches of the contact search (theory.md §2.7): the first
/// candidates (contact::initial_candidates of the free displacement, or `first_candidates` if
/// given: increasing patch indices), then one more solve with the left-out patches that
/// penetrate added, until none does. Builds the dual operator of each set (phase "dual") by
/// `operators` (make_candidate_operators: on the backend's factor of K or its subdomains), fills
/// the contact part of r.report (over every patch) and r.contact, and returns the displacement
/// over the free dofs.
VectorXd solve_with_search(const Problem& problem, const contact::ContactDiscretization& disc,
                           const RunOptions& options, RunResult& r, CandidateOperators& operators,
                           const std::vector<Index>* first_candidates = nullptr);

/// Against curved rigid obstacles (theory.md §2.11): how far the linearized gap of `disc` is from
/// the true one at the solution u (over the free dofs, with r.model's prescribed values) at the
/// nodes in contact (r.contact's patch states), into r.report.contact's geometry fields with
/// `updates_done`; whether it is within contact.geometry_tolerance (true without such a pair).
bool measure_linearization(const Problem& problem, const contact::ContactDiscretization& disc,
                           const VectorXd& u, int updates_done, RunResult& r);

/// Against curved rigid obstacles (theory.md §2.11), after the solve u of `disc`: while the
/// linearized gap is off the true one by more than contact.geometry_tolerance, at most
/// contact.geometry_updates times, the discretization is made again at the deformed position
/// (the obstacles where `obstacles` puts them, one per pair; null: a static run's) and
/// `solve_again` solves it (filling r as the first solve did); the report counts the work of
/// every solve. Returns the last displacement over the free dofs (u itself without such a pair).
VectorXd update_geometry(
    const Problem& problem, const contact::ContactDiscretization& disc, VectorXd u,
    const RunOptions& options, RunResult& r,
    const std::function<VectorXd(const contact::ContactDiscretization&)>& solve_again,
    const std::vector<Vec3>* obstacles = nullptr);

/// The model's sizes in the report (nodes, tetrahedra, free dofs).
void report_sizes(const Model& model, RunReport& report);

/// ||K u - f|| / ||f|| of an elastic solve u (no contact).
Real elastic_residual(const Model& model, const VectorXd& u);

/// The end of a run from its displacement u over the free dofs: stresses, and the global
/// equilibrium of applied loads, contact forces and reactions (phase "postprocess"). The status
/// stays the solve's: a stop requested after the solve converged (during its certificate, or
/// here) leaves a converged, certified answer converged.
/// Without `with_stresses` the stresses are left as they were (a step of a loading path that
/// nobody watches: compute_stresses later).
void finish_run(const Problem& problem, const VectorXd& u, RunResult& r, bool with_stresses = true);

/// The stresses and von Mises stresses of r.displacement, into r.
void compute_stresses(RunResult& r);

}  // namespace fricon::driver
