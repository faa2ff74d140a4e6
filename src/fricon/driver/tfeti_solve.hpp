#pragma once
// driver: backend "tfeti" (docs/theory.md §8) in the run: the Total FETI operator of a model,
// built in place of the factor of K, and the elastic solve of a model without contact by the same
// dual QP (its multipliers all equality ones). With contact the operator goes to the contact
// solve like any dual::DualOperator.

#include <memory>

#include "fricon/contact/discretization.hpp"
#include "fricon/driver/model.hpp"
#include "fricon/driver/problem.hpp"
#include "fricon/driver/run.hpp"
#include "fricon/feti/feti_operator.hpp"
#include "fricon/qp/smalse.hpp"

namespace fricon::driver {

/// The Total FETI operator of the model (assemble_loads: no K) with the contact rows of `disc`
/// (null: none), from the problem's [solver] subdomains, subdomain_size and tfeti_scaling, its
/// subdomain loops on the run's threads (linalg::threads(), the BLAS then on one: the parallelism
/// is over the subdomains), shared with the processes of options.feti_ranks (collective over
/// them). Fills report.feti; phase "factorize". Throws InputError for a partition that cannot be
/// made (naming solver.subdomains), NumericalError for a subdomain that cannot be factored.
std::unique_ptr<feti::FetiOperator> make_feti_operator(const Problem& problem, const Model& model,
                                                       const contact::ContactDiscretization* disc,
                                                       const RunOptions& options,
                                                       RunReport& report);

/// After a contact solve with `F`: its products with F and coarse solves into report.feti, and
/// each process's share of the multipliers (collective over F.ranks()); the peak memory comes at
/// the run's end (record_run_peak_memory).
void record_feti_counts(const feti::FetiOperator& F, RunReport& report);

/// At the end of a run with backend "tfeti" (report.feti set; otherwise nothing): the processes'
/// peak memory over the whole run, the fields and the self-check included, into report.feti.
/// Collective over options.feti_ranks (this process alone when null).
void record_run_peak_memory(const RunOptions& options, RunReport& report);

/// The displacement of F's load with its subdomains held by the gluing and Dirichlet rows alone
/// (no contact), and the certificate's figures of it.
struct GluingSolve {
  VectorXd u;  ///< over the model's free dofs [m]
  qp::SmalseReport qp;
  Real gluing_residual = 0.0;  ///< FetiOperator::gluing_residual
  Real gluing_bound = 0.0;     ///< 100 qp_rtol: the certificate's bound on it
  bool converged() const {
    return qp.termination == qp::QpTermination::Converged && gluing_residual <= gluing_bound;
  }
};

/// SMALSE-M on the equality multipliers of F, which must have no contact rows (free unknowns,
/// with the equality G lambda = e), to kEqualityToleranceShare of solver.qp_rtol, then the
/// displacement u = K^+ (f - B^T lambda) + R alpha. Collective over F.ranks(). Throws
/// Interrupted when a stop is requested during the QP.
GluingSolve solve_gluing(const feti::FetiOperator& F, const Problem& problem,
                         const RunOptions& options);

/// The contact search's free displacement under Total FETI (theory.md §8.7): solve_gluing's u,
/// the load held by the gluing and Dirichlet rows alone (F must have no contact rows). A solve
/// that did not converge still gives u, which only chooses the first candidates (the search's
/// last round checks every patch with its own solve), and says why in
/// report.feti->free_displacement_note, which the run's warnings repeat.
VectorXd gluing_free_displacement(const feti::FetiOperator& F, const Problem& problem,
                                  const RunOptions& options, RunReport& report);

/// The displacement over the free dofs of a model without contact by Total FETI: SMALSE-M on the
/// gluing and Dirichlet multipliers (free unknowns) with the equality G lambda = e (phase
/// "solve"). Sets the report's status, message, linear residual and the gluing residual of the
/// certificate; a QP that did not converge, or whose gluing residual exceeds 100 qp_rtol, leaves
/// the status NotConverged.
VectorXd solve_elastic_tfeti(const Problem& problem, const RunOptions& options, RunResult& r);

}  // namespace fricon::driver
