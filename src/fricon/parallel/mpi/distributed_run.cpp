// parallel/mpi: driver::run on the ranks of an MPI job (docs/parallel.md, docs/theory.md §3.3).
//   rank 0       the whole model without K (mesh, dofs, f for the residuals) and the contact
//                discretization -> partition of the tetrahedra -> to each rank its part of the
//                model (its tetrahedra and their nodes, numbered within the part) and to every
//                rank B on the contact dofs
//   every rank   the entries of K and the part of f of its own tetrahedra
//   all ranks    one MUMPS factorization (of K, or of [[K, B^T], [B, 0]] with Q as its Schur
//                complement on rank 0)
//   rank 0       dual operator -> outer loop of dual QPs -> postprocessing, while the others
//                follow its distributed solves (DistributedSolves: right-hand sides and
//                solutions stay distributed; rank 0 receives n_dual numbers per product with Q,
//                the contact dofs per outer iteration, and the displacement once at the end)
// No rank is left waiting (docs/parallel.md, "When a rank fails"): every step that may fail on
// some ranks and makes no collective call runs in collectively(), and rank 0 ends the others'
// follow() with its status or its error; an error that leaves run_distributed on one rank
// alone (one inside a step of collective calls: the partition, MUMPS, a distributed solve)
// ends the job with MPI_Abort, exit code 3 (or_abort()).
#include <memory>
#include <mutex>
#include <optional>

#include "fricon/core/error.hpp"
#include "fricon/driver/run_steps.hpp"
#include "fricon/fe/assembly.hpp"
#include "fricon/linalg/blas.hpp"
#include "fricon/linalg/cholesky.hpp"
#include "fricon/parallel/distributed_run.hpp"
#include "fricon/parallel/mpi/command_channel.hpp"
#include "fricon/parallel/mpi/distributed_solves.hpp"
#include "fricon/parallel/mpi/mumps_factor.hpp"
#include "fricon/parallel/mpi/mumps_operator.hpp"
#include "fricon/parallel/mpi/partition.hpp"
#include "fricon/parallel/mpi/scatter_model.hpp"
#include "fricon/parallel/mpi/session.hpp"
#include "fricon/parallel/mpi/test_fault.hpp"

namespace fricon::parallel {

namespace {

// The distributed operator carries no balance G lambda = e (theory.md §2.10): a floating body is
// refused by name, before any factorization.
void refuse_floating_bodies(const driver::Problem& problem, const driver::Model& model) {
  if (model.floating.empty()) return;
  const fe::FloatingBody& body = model.floating.bodies.front();
  throw InputError(fmt::format(
      "{}: solver.backend: {} floats (its [[dirichlet]] conditions leave {} rigid motion(s) "
      "free, held by contact), and the backend \"petsc\" does not solve floating bodies; use "
      "backend \"cholmod\" (one process), or hold the body by [[dirichlet]] conditions",
      problem.where("solver.backend"), mesh::describe_body(model.mesh, model.bodies, body.body),
      body.n_motions()));
}

using driver::RunOptions;
using driver::RunResult;

// The lower triangle of this rank's part of K (in the whole model's numbering) and, when B is
// given (rank 0 of a Schur factorization), the block B below K in the augmented matrix.
LocalEntries local_entries(const driver::ModelPart& part, const SparseMatrix* B) {
  LocalEntries e;
  {
    const driver::Model& m = part.model;
    const SparseMatrix K_part = fe::assemble_stiffness(m.mesh, m.materials, m.dofs);
    const Index n_lower = (K_part.nonZeros() + K_part.rows()) / 2;
    e.rows.reserve(static_cast<std::size_t>(n_lower));
    e.cols.reserve(static_cast<std::size_t>(n_lower));
    e.values.reserve(static_cast<std::size_t>(n_lower));
    // global_dof is ascending: the lower triangle of the part is in the lower triangle of K.
    const std::vector<Index>& global = part.global_dof;
    for (Index j = 0; j < K_part.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(K_part, j); it; ++it)
        if (it.row() >= j)
          e.add(global[static_cast<std::size_t>(it.row())], global[static_cast<std::size_t>(j)],
                it.value());
  }
  if (B != nullptr) {
    const Index n_free = B->cols();
    for (Index j = 0; j < B->outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(*B, j); it; ++it)
        e.add(n_free + it.row(), j, it.value());
  }
  return e;
}

// The elimination order of the free dofs given to MUMPS (rank 0): the nested dissection of the
// node graph that the CHOLMOD backend uses (linalg::nested_dissection; Debian's MUMPS has no
// METIS or SCOTCH of its own, and its AMD fills the factor of a 3D mesh far more), each node's
// free dofs together.
std::vector<Index> free_dof_order(const driver::Model& m) {
  const fe::NodeGraph graph = fe::node_graph(m.mesh);
  std::vector<Index> order;
  order.reserve(static_cast<std::size_t>(m.dofs.n_free()));
  for (Index node : linalg::nested_dissection(graph.start, graph.adj))
    for (int c = 0; c < 3; ++c)
      if (const Index dof = m.dofs.dof(node, c); dof >= 0) order.push_back(dof);
  return order;
}

// [solver] memory_per_rank as MUMPS is given it.
MemoryLimit memory_limit(const driver::Problem& problem) {
  const std::optional<Real>& mib = problem.solver.memory_per_rank;
  if (!mib) return {};
  return {*mib, problem.where("solver.memory_per_rank"), "solver.memory_per_rank"};
}

// The factor's figures in the report's terms.
linalg::CholeskyInfo factor_info(const MumpsInfo& m) {
  linalg::CholeskyInfo i;
  i.n = m.n;
  i.nnz_K = static_cast<Index>(m.nnz_A);
  i.nnz_L = m.nnz_factor;
  i.flops = m.flops;
  i.supernodal = false;  // multifrontal
  i.ordering = m.ordering;
  i.rcond = 0.0;  // MUMPS gives no estimate here
  i.blas_threads = linalg::threads();
  return i;
}

// What the other ranks need to know of rank 0's model: its number of free dofs and whether it
// has contact. Collective.
struct ModelSizes {
  Index n_free = 0;
  bool contact = false;
};

ModelSizes broadcast_sizes(const driver::Model& m, bool contact, MPI_Comm comm) {
  long sizes[2] = {static_cast<long>(m.dofs.n_free()), contact ? 1 : 0};
  MPI_Bcast(sizes, 2, MPI_LONG, 0, comm);
  return {static_cast<Index>(sizes[0]), sizes[1] != 0};
}

// B on the contact dofs, from rank 0's discretization to every rank (none without contact).
// Collective.
std::optional<ContactCoupling> share_contact(
    const std::optional<contact::ContactDiscretization>& disc, bool contact, int rank) {
  if (!contact) return std::nullopt;
  ContactCoupling c = rank == 0 ? ContactCoupling::of(disc->B, disc->dofs) : ContactCoupling{};
  c.broadcast(world());
  return c;
}

// What a rank gives MUMPS of K and f, from its own part of the model, and what it held.
struct RankShare {
  LocalEntries entries;  // of K (and B, on rank 0 of a Schur factorization)
  LoadPart load;         // of f
  Index n_tets = 0;      // of its part
  Index n_nodes = 0;     // held: all on rank 0, its part's elsewhere
  double model_mib = 0;  // its peak once its input was built
};

// The partition, each rank's part of the model from rank 0 (`whole`, null elsewhere), and the
// part's share of K and f (phases "partition", "assembly"). Collective.
RankShare assemble_share(const driver::Problem& problem, const driver::Model* whole,
                         const SparseMatrix* B, PartitionKind partition, PhaseTimes& times) {
  RankShare share;
  driver::ModelPart part;
  {
    ScopedPhase phase(times, "partition");
    // (partition_elements agrees on its failures or ends the job itself)
    const std::vector<int> owner =
        partition_elements(whole ? &whole->mesh : nullptr, partition, world());
    collectively([&] { part = scatter_model(problem, whole, owner, world()); });
  }
  share.model_mib = peak_memory_mib();
  share.n_tets = part.model.mesh.n_tets();
  share.n_nodes = whole ? whole->mesh.n_nodes() : part.model.mesh.n_nodes();
  collectively([&] {
    ScopedPhase phase(times, "assembly");
    test_fault("assembly");
    share.entries = local_entries(part, B);
    share.load = LoadPart::of(driver::load_vector(problem, part.model, driver::Extent::Part),
                              part.global_dof);
  });
  return share;  // (the part is freed: MUMPS gets the entries)
}

// Every rank's figures, on rank 0. Collective.
std::vector<RankReport> gather_ranks(const RankShare& share, const MumpsInfo& info, int rank,
                                     int size) {
  constexpr int kFigures = 6;
  const double mine[kFigures] = {static_cast<double>(share.n_tets),
                                 peak_memory_mib(),
                                 info.memory_mib,
                                 info.estimate_mib,
                                 share.model_mib,
                                 static_cast<double>(share.n_nodes)};
  test_fault("gather");
  std::vector<double> all(static_cast<std::size_t>(kFigures * size));
  MPI_Gather(mine, kFigures, MPI_DOUBLE, all.data(), kFigures, MPI_DOUBLE, 0, world());
  std::vector<RankReport> ranks;
  if (rank != 0) return ranks;
  for (int r = 0; r < size; ++r) {
    const double* a = &all[static_cast<std::size_t>(kFigures * r)];
    ranks.push_back({static_cast<Index>(a[0]), static_cast<Index>(a[5]), a[1], a[2], a[3], a[4]});
  }
  return ranks;
}

// Rank 0: the dual operator on the distributed solves and the outer loop of dual QPs, or without
// contact one solve. Returns the displacement over the free dofs; its solves are collective with
// the other ranks' DistributedSolves::follow().
VectorXd solve_on_rank_0(const driver::Problem& problem,
                         const std::optional<contact::ContactDiscretization>& disc,
                         dual::DualOperatorKind kind, const MumpsFactor& factor,
                         const DistributedSolves& solves, const RunOptions& opts, RunResult& r) {
  driver::RunReport& rep = r.report;
  if (opts.stop_was_requested()) throw Interrupted("interrupted before the solve");
  if (!disc) {
    ScopedPhase phase(rep.times, "solve");
    VectorXd u = solves.displacement(VectorXd());
    rep.linear_residual = driver::elastic_residual(r.model, u);
    return u;
  }
  driver::phase_start(opts, "dual");
  std::unique_ptr<dual::DualOperator> Q;
  {
    ScopedPhase phase(rep.times, "dual");
    Q = make_mumps_operator(kind, solves, &factor.schur(), disc->B, &disc->offset);
  }
  VectorXd u = driver::solve_with_operator(problem, *disc, *Q, opts, r);
  // Every rank holds B (DistributedSolves): the reference linearization is kept, and its error
  // reported (theory.md §2.11).
  (void)driver::measure_linearization(problem, *disc, u, 0, r);
  return u;
}

// run_distributed on this rank, MPI started; the factor is made in `factor`.
RunResult run_on_rank(const driver::Problem& problem, const RunOptions& options,
                      std::unique_ptr<MumpsFactor>& factor) {
  const Stopwatch total;
  const int rank = world_rank(), size = world_size();
  // Progress and callbacks come from rank 0 only; a stop request reaches rank 0's outer loop.
  RunOptions quiet;
  quiet.stop_requested = options.stop_requested;
  const RunOptions& opts = rank == 0 ? options : quiet;
  RunResult r;
  driver::RunReport& rep = r.report;
  ParallelReport par;
  par.rank = rank;
  par.n_ranks = size;
  par.partition = problem.solver.partition;

  // @sect: rank 0: the model without K, and the contact discretization; every rank checks
  // its problem.
  std::optional<contact::ContactDiscretization> disc;
  collectively([&] {
    test_fault("model");
    driver::validate(problem);
    if (rank != 0) return;
    // f whole on rank 0, for the residuals of the postprocessing; every rank assembles its
    // part of it below.
    r.model = driver::assemble_loads(problem, rep.times, opts.on_phase_start);
    // The checks of driver::run before the factorization (driver::check_model), the same here.
    if (problem.contact.empty()) {
      (void)driver::check_model(problem, r.model);
    } else {
      driver::phase_start(opts, "contact");
      ScopedPhase phase(rep.times, "contact");
      disc = driver::check_model(problem, r.model);
    }
    refuse_floating_bodies(problem, r.model);
  });
  const ModelSizes sizes = broadcast_sizes(r.model, disc.has_value(), world());
  test_fault("share");  // (between two broadcasts: the job ends, see run_distributed)
  const std::optional<ContactCoupling> contact = share_contact(disc, sizes.contact, rank);
  const dual::DualOperatorKind kind =
      contact ? dual::resolve(problem.solver.dual_operator, dual::FactorLocation::Distributed,
                              contact->B.rows())
              : dual::DualOperatorKind::Implicit;
  const bool with_schur = contact && kind == dual::DualOperatorKind::Schur;
  par.n_schur = with_schur ? contact->B.rows() : 0;

  // @sect: the partition; each rank's part of the model, and its part of K (and B, on rank 0)
  // and of f.
  driver::phase_start(opts, "partition");
  RankShare share =
      assemble_share(problem, rank == 0 ? &r.model : nullptr,
                     with_schur && rank == 0 ? &disc->B : nullptr, par.partition, rep.times);

  // @sect: one factorization across the ranks.
  driver::phase_start(opts, "factorize");
  {
    ScopedPhase phase(rep.times, "factorize");
    std::vector<Index> order;
    collectively([&] {
      if (rank == 0) order = free_dof_order(r.model);
    });
    // (MumpsFactor agrees on its failures or ends the job itself)
    factor = std::make_unique<MumpsFactor>(world(), sizes.n_free, par.n_schur,
                                           std::move(share.entries), order, memory_limit(problem));
  }

  // @sect: the ranks other than 0 take part in rank 0's solves until it ends the run.
  const CommandChannel channel(world());
  std::optional<DistributedSolves> solves;
  collectively([&] {
    test_fault("setup");
    solves.emplace(*factor, channel, contact ? &*contact : nullptr, std::move(share.load));
  });
  if (rank != 0) {
    driver::phase_start(options, "follow");  // (a stop request is rank 0's to act on)
    rep.status = static_cast<driver::RunStatus>(solves->follow());
    par.ranks = gather_ranks(share, factor->info(), rank, size);
    rep.parallel = par;
    return r;
  }

  // @sect: rank 0: the displacement, then the fields; the other ranks wait until it ends, with
  // its error if it fails (the same on every rank from here: Agreed).
  try {
    driver::report_sizes(r.model, rep);
    rep.factor = factor_info(factor->info());
    par.analysis_s = factor->info().analysis_s;
    par.factorization_s = factor->info().factorization_s;
    const VectorXd u = solve_on_rank_0(problem, disc, kind, *factor, *solves, opts, r);
    driver::finish_run(problem, u, r);
  } catch (...) {
    const ErrorPacket error = capture_current_exception();
    channel.fail(error);
    raise(error);
  }
  channel.finish(static_cast<int>(rep.status));
  par.ranks = gather_ranks(share, factor->info(), rank, size);
  rep.parallel = par;
  rep.time_s = total.seconds();
  return r;
}

}  // namespace

RunResult run_distributed(const driver::Problem& problem, const RunOptions& options) {
  // PETSc and MPI are the process's and fricon calls them from one thread (MPI is started
  // without thread support): a second distributed run while one runs, from another thread of
  // the process (fricon.solve from Python threads), is refused rather than left to race.
  static std::mutex one_run_at_a_time;
  const std::unique_lock busy(one_run_at_a_time, std::try_to_lock);
  if (!busy.owns_lock())
    throw Error(
        "solver.backend = \"petsc\": another solve with the PETSc backend is running in this "
        "process (from another thread); PETSc runs one solve at a time per process: wait for it, "
        "or use backend \"cholmod\", which runs concurrently (docs/python.md, \"Threads\")");
  initialize();
  // The other ranks would wait forever for a rank that leaves with an error they do not raise
  // too: what the steps agree on (Agreed) passes, anything else ends the job. The factor
  // outlives the guard: its destructor is collective (MUMPS's end), and a rank failing alone
  // must not reach it.
  std::unique_ptr<MumpsFactor> factor;
  RunResult r;
  or_abort([&] { r = run_on_rank(problem, options, factor); });
  return r;
}

}  // namespace fricon::parallel
