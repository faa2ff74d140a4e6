// The measurement behind the PETSc backend's design (docs/petsc-backend.md): on P MPI ranks,
// two ways of forming the dual Hessian Q = B K^-1 B^T of the paper's brick with MUMPS through
// PETSc, against fricon's own Q (CHOLMOD, forward operator) on the same discrete problem:
//   schur    MUMPS on the augmented matrix [[K, B^T], [B, 0]] with the multipliers as Schur
//            variables (centralized on rank 0): Q = -S; and whether MatSolve then still works
//            with that factor (the solves for the displacement need it)
//   columns  MUMPS Cholesky of K alone, Q = B X with K X = B^T solved in blocks of columns
//   direct   MUMPS called directly on the augmented matrix (distributed entries, Schur variables
//            centralized): Q = -S, and the interior solve with the same factor gives K^-1 f
// Run: mpirun -n P build/bench/petsc_schur_probe [n] [--try-solve]   (n: mesh parameter, default
// 8; --try-solve: try MatSolve with the Schur factor on several ranks too, which hangs with
// PETSc 3.18; --help: the options)
// The model is built on every rank (replicated input; each rank inserts its own rows).

#include <dmumps_c.h>
#include <petscmat.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "common/bench_args.hpp"
#include "common/child_process.hpp"
#include "fricon/core/timer.hpp"
#include "fricon/driver/model.hpp"
#include "fricon/dual/dual_operator.hpp"
#include "fricon/io/problem_file.hpp"

namespace {

using fricon::Index;
using fricon::MatrixXd;
using fricon::SparseMatrix;

constexpr PetscInt kColumnsPerBlock = 256;  // right-hand sides per MatMatSolve of "columns"
constexpr double kAgreement = 1e-9;         // max |Q - Q_cholmod| / max |Q| the test accepts

void check(PetscErrorCode e, const char* what) {
  if (e != 0) throw fricon::NumericalError(fmt::format("PETSc: {} failed (error {})", what, e));
}

// Rows [rs, re) of the symmetric matrix [[K, B^T], [B, 0]] (or K alone when B is null), from the
// replicated column-major K and B, each rank its own rows, preallocated from their pattern (COO).
Mat assemble(const SparseMatrix& K, const SparseMatrix* B) {
  const PetscInt n = K.rows(), m = B ? B->rows() : 0, N = n + m;
  PetscInt local = PETSC_DECIDE, global = N, re = 0;
  check(PetscSplitOwnership(PETSC_COMM_WORLD, &local, &global), "PetscSplitOwnership");
  check(MPI_Scan(&local, &re, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD), "MPI_Scan");
  const PetscInt rs = re - local;
  Mat A;
  check(MatCreate(PETSC_COMM_WORLD, &A), "MatCreate");
  check(MatSetSizes(A, local, local, N, N), "MatSetSizes");
  check(MatSetType(A, MATAIJ), "MatSetType");
  std::vector<PetscInt> rows, cols;
  std::vector<PetscScalar> values;
  const auto add = [&](PetscInt i, PetscInt j, PetscScalar v) {
    rows.push_back(i), cols.push_back(j), values.push_back(v);
  };
  const SparseMatrix Bt = B ? SparseMatrix(B->transpose()) : SparseMatrix();
  for (PetscInt j = rs; j < std::min(re, n); ++j) {  // row j of K = column j (K symmetric)
    for (SparseMatrix::InnerIterator it(K, j); it; ++it)
      add(j, it.row(), it.value());
    if (B)
      for (SparseMatrix::InnerIterator it(*B, j); it; ++it)
        add(j, n + it.row(), it.value());
  }
  for (PetscInt i = std::max(rs, n); i < re; ++i) {  // row i - n of B, and a zero diagonal
    for (SparseMatrix::InnerIterator it(Bt, i - n); it; ++it)
      add(i, it.row(), it.value());
    add(i, i, 0.0);
  }
  check(MatSetPreallocationCOO(A, static_cast<PetscCount>(rows.size()), rows.data(), cols.data()),
        "MatSetPreallocationCOO");
  check(MatSetValuesCOO(A, values.data(), INSERT_VALUES), "MatSetValuesCOO");
  check(MatSetOption(A, MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
  if (!B) check(MatSetOption(A, MAT_SPD, PETSC_TRUE), "MatSetOption");
  return A;
}

double relative_difference(const MatrixXd& a, const MatrixXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

enum class SolveCheck { Works, Refused, NotTried };

// "schur": Q = -S from the augmented factor; and whether MatSolve works with it. On more than one
// rank PETSc 3.18 refuses on rank 0 only while the others enter MUMPS and wait forever, so it is
// tried there only when asked (try_solve).
std::pair<MatrixXd, SolveCheck> schur_way(const SparseMatrix& K, const SparseMatrix& B, int rank,
                                          int size, bool try_solve) {
  const PetscInt n = K.rows(), m = B.rows();
  Mat A = assemble(K, &B), F, S;
  IS schur;
  check(ISCreateStride(PETSC_COMM_SELF, rank == 0 ? m : 0, n, 1, &schur), "ISCreateStride");
  check(MatGetFactor(A, MATSOLVERMUMPS, MAT_FACTOR_CHOLESKY, &F), "MatGetFactor");
  check(MatFactorSetSchurIS(F, schur), "MatFactorSetSchurIS");
  MatFactorInfo info;
  check(MatFactorInfoInitialize(&info), "MatFactorInfoInitialize");
  check(MatCholeskyFactorSymbolic(F, A, nullptr, &info), "MatCholeskyFactorSymbolic");
  check(MatCholeskyFactorNumeric(F, A, &info), "MatCholeskyFactorNumeric");
  MatFactorSchurStatus status;
  check(MatFactorCreateSchurComplement(F, &S, &status), "MatFactorCreateSchurComplement");
  MatrixXd Q = MatrixXd::Zero(m, m);
  if (rank == 0) {
    const PetscScalar* s = nullptr;
    check(MatDenseGetArrayRead(S, &s), "MatDenseGetArrayRead");
    Q = -Eigen::Map<const MatrixXd>(s, m, m);
    check(MatDenseRestoreArrayRead(S, &s), "MatDenseRestoreArrayRead");
  }
  check(MPI_Bcast(Q.data(), static_cast<int>(Q.size()), MPI_DOUBLE, 0, PETSC_COMM_WORLD),
        "MPI_Bcast");
  // Whether the same factor solves K w = r (the displacement): PETSc's answer, not an abort.
  SolveCheck solves = SolveCheck::NotTried;
  if (size == 1 || try_solve) {
    Vec b, x;
    check(MatCreateVecs(A, &x, &b), "MatCreateVecs");
    check(VecSet(b, 1.0), "VecSet");
    check(PetscPushErrorHandler(PetscReturnErrorHandler, nullptr), "PetscPushErrorHandler");
    solves = MatSolve(F, b, x) == 0 ? SolveCheck::Works : SolveCheck::Refused;
    check(PetscPopErrorHandler(), "PetscPopErrorHandler");
    VecDestroy(&b), VecDestroy(&x);
  }
  MatDestroy(&S), MatDestroy(&F), MatDestroy(&A), ISDestroy(&schur);
  return {Q, solves};
}

// "columns": Q = B K^-1 B^T by solves with the MUMPS factor of K alone, kColumnsPerBlock at once.
MatrixXd columns_way(const SparseMatrix& K, const SparseMatrix& B) {
  const PetscInt n = K.rows(), m = B.rows();
  Mat A = assemble(K, nullptr), F;
  check(MatGetFactor(A, MATSOLVERMUMPS, MAT_FACTOR_CHOLESKY, &F), "MatGetFactor");
  MatFactorInfo info;
  check(MatFactorInfoInitialize(&info), "MatFactorInfoInitialize");
  check(MatCholeskyFactorSymbolic(F, A, nullptr, &info), "MatCholeskyFactorSymbolic");
  check(MatCholeskyFactorNumeric(F, A, &info), "MatCholeskyFactorNumeric");
  PetscInt rs = 0, re = 0;
  check(MatGetOwnershipRange(A, &rs, &re), "MatGetOwnershipRange");
  const SparseMatrix Bt = B.transpose();
  MatrixXd Q = MatrixXd::Zero(m, m);
  for (PetscInt c0 = 0; c0 < m; c0 += kColumnsPerBlock) {
    const PetscInt nc = std::min(kColumnsPerBlock, m - c0);
    Mat R, X;
    check(MatCreateDense(PETSC_COMM_WORLD, re - rs, PETSC_DECIDE, n, nc, nullptr, &R),
          "MatCreateDense");
    check(MatCreateDense(PETSC_COMM_WORLD, re - rs, PETSC_DECIDE, n, nc, nullptr, &X),
          "MatCreateDense");
    PetscScalar* r = nullptr;
    check(MatDenseGetArray(R, &r), "MatDenseGetArray");
    const Index local = re - rs;
    std::fill(r, r + local * nc, 0.0);
    for (PetscInt c = 0; c < nc; ++c)
      for (SparseMatrix::InnerIterator it(Bt, c0 + c); it; ++it)
        if (it.row() >= rs && it.row() < re) r[c * local + (it.row() - rs)] = it.value();
    check(MatDenseRestoreArray(R, &r), "MatDenseRestoreArray");
    check(MatMatSolve(F, R, X), "MatMatSolve");
    const PetscScalar* x = nullptr;
    check(MatDenseGetArrayRead(X, &x), "MatDenseGetArrayRead");
    // Q[:, block] = B X: each rank its own rows of X, summed over the ranks.
    const Eigen::Map<const MatrixXd> Xl(x, local, nc);
    Q.middleCols(c0, nc) = B.middleCols(rs, local) * Xl;
    check(MatDenseRestoreArrayRead(X, &x), "MatDenseRestoreArrayRead");
    MatDestroy(&R), MatDestroy(&X);
  }
  check(MPI_Allreduce(MPI_IN_PLACE, Q.data(), static_cast<int>(Q.size()), MPI_DOUBLE, MPI_SUM,
                      PETSC_COMM_WORLD),
        "MPI_Allreduce");
  MatDestroy(&F), MatDestroy(&A);
  return Q;
}

// "direct": MUMPS called directly (dmumps_c), the design docs/petsc-backend.md arrives at: the
// augmented matrix in distributed form (each rank the lower-triangle entries of its block of
// rows), the multipliers as Schur variables centralized on rank 0, one factorization; Q = -S, and
// the interior solve (ICNTL(26) = 0) with the same factor gives u0 = K^-1 f on rank 0.
struct Direct {
  MatrixXd Q;
  fricon::VectorXd u0;
};
Direct direct_way(const SparseMatrix& K, const SparseMatrix& B, const fricon::VectorXd& f, int rank,
                  int size) {
  const Index n = K.rows(), m = B.rows(), N = n + m;
  const auto owner = [&](Index i) { return static_cast<int>(i * size / N); };
  std::vector<MUMPS_INT> irn, jcn;  // 1-based
  std::vector<double> a;
  const auto add = [&](Index i, Index j, double v) {
    irn.push_back(static_cast<MUMPS_INT>(i + 1)), jcn.push_back(static_cast<MUMPS_INT>(j + 1));
    a.push_back(v);
  };
  for (Index j = 0; j < n; ++j)
    for (SparseMatrix::InnerIterator it(K, j); it; ++it)
      if (it.row() >= j && owner(it.row()) == rank) add(it.row(), j, it.value());
  for (Index j = 0; j < n; ++j)
    for (SparseMatrix::InnerIterator it(B, j); it; ++it)
      if (owner(n + it.row()) == rank) add(n + it.row(), j, it.value());
  DMUMPS_STRUC_C id{};
  id.comm_fortran = static_cast<MUMPS_INT>(MPI_Comm_c2f(PETSC_COMM_WORLD));
  id.par = 1;  // the host works too
  id.sym = 2;  // symmetric, not definite
  id.job = -1;
  dmumps_c(&id);
  id.icntl[0] = id.icntl[1] = id.icntl[2] = -1;  // no output
  id.icntl[3] = 0;
  id.icntl[17] = 3;  // ICNTL(18): distributed entries
  id.n = static_cast<MUMPS_INT>(N);
  id.nnz_loc = static_cast<MUMPS_INT8>(a.size());
  id.irn_loc = irn.data(), id.jcn_loc = jcn.data(), id.a_loc = a.data();
  std::vector<MUMPS_INT> schur_vars;
  MatrixXd S = MatrixXd::Zero(m, m);
  id.icntl[18] = 1;  // ICNTL(19): Schur complement centralized on the host
  id.size_schur = static_cast<MUMPS_INT>(m);
  if (rank == 0) {
    for (Index k = 0; k < m; ++k)
      schur_vars.push_back(static_cast<MUMPS_INT>(n + k + 1));
    id.listvar_schur = schur_vars.data();
    id.schur = S.data();
  }
  id.job = 4;  // analysis and factorization
  dmumps_c(&id);
  if (id.infog[0] < 0)
    throw fricon::NumericalError(fmt::format("MUMPS factorization: INFOG(1) = {}", id.infog[0]));
  Direct out{MatrixXd::Zero(m, m), fricon::VectorXd::Zero(n)};
  std::vector<double> rhs(static_cast<std::size_t>(rank == 0 ? N : 0), 0.0);
  if (rank == 0) {
    // One triangle of the symmetric S is returned; complete it.
    const bool lower = S.triangularView<Eigen::StrictlyUpper>().toDenseMatrix().isZero(0.0);
    const MatrixXd T = lower ? MatrixXd(S.triangularView<Eigen::Lower>())
                             : MatrixXd(S.triangularView<Eigen::Upper>());
    out.Q = -(T + T.transpose() - MatrixXd(T.diagonal().asDiagonal()));
    std::copy(f.data(), f.data() + n, rhs.begin());
    id.rhs = rhs.data(), id.nrhs = 1, id.lrhs = static_cast<MUMPS_INT>(N);
  }
  id.icntl[25] = 0;  // ICNTL(26): solve the interior problem (with K)
  id.icntl[19] = 0;  // ICNTL(20): dense centralized right-hand side
  id.icntl[20] = 0;  // ICNTL(21): centralized solution
  id.job = 3;
  dmumps_c(&id);
  const int solved = id.infog[0];
  id.job = -2;
  dmumps_c(&id);
  if (solved < 0) throw fricon::NumericalError(fmt::format("MUMPS solve: INFOG(1) = {}", solved));
  if (rank == 0) out.u0 = Eigen::Map<const fricon::VectorXd>(rhs.data(), n);
  return out;
}

// The probe on every rank of the job; its exit code.
int probe(int argc, char** argv, int n, bool try_solve) {
  if (PetscInitialize(&argc, &argv, nullptr, nullptr) != 0) return 1;
  int rank = 0, size = 1;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  int status = 0;
  try {
    const fricon::driver::Problem problem =
        fricon::io::read_problem(FRICON_SOURCE_DIR "/examples/paper-brick.toml",
                                 {fmt::format("mesh.cells=[{},{},{}]", 3 * n, n, n)});
    fricon::PhaseTimes times;
    fricon::driver::Model model = fricon::driver::assemble_model(problem, times, {});
    const auto disc = fricon::driver::discretize_contact(problem, model.mesh, model.dofs);

    fricon::Stopwatch clock;
    fricon::driver::factorize_model(model, {}, times, {});
    const fricon::dual::DualInput input{model.factor, disc.B, model.f, disc.dofs, {}, &disc.offset};
    const MatrixXd Q =
        fricon::dual::make_dual_operator(fricon::dual::DualOperatorKind::Forward, input)
            ->to_dense();
    const double cholmod_s = clock.seconds();

    clock = fricon::Stopwatch();
    const auto [Qs, solves] = schur_way(model.K, disc.B, rank, size, try_solve);
    const double schur_s = clock.seconds();
    clock = fricon::Stopwatch();
    const MatrixXd Qc = columns_way(model.K, disc.B);
    const double columns_s = clock.seconds();
    clock = fricon::Stopwatch();
    const Direct direct = direct_way(model.K, disc.B, model.f, rank, size);
    const double direct_s = clock.seconds();
    const fricon::VectorXd u0 = model.factor.solve(model.f);
    const double u0_difference = (direct.u0 - u0).cwiseAbs().maxCoeff() / u0.cwiseAbs().maxCoeff();
    const double peak_mib = fricon::bench::peak_mib();

    if (rank == 0) {
      fmt::print(
          "petsc_schur_probe: paper brick n = {}, {} free dofs, {} multipliers, {} rank(s)\n", n,
          model.K.rows(), disc.B.rows(), size);
      fmt::print("  cholmod forward   Q in {:7.3f} s (factor + Q, one process)\n", cholmod_s);
      fmt::print(
          "  mumps schur       Q in {:7.3f} s, max |Q - Q_cholmod| / max |Q| = {:.2e}, "
          "MatSolve with this factor: {}\n",
          schur_s, relative_difference(Qs, Q),
          solves == SolveCheck::Works     ? "works"
          : solves == SolveCheck::Refused ? "refused"
                                          : "not tried on several ranks (--try-solve)");
      fmt::print(
          "  mumps columns     Q in {:7.3f} s, max |Q - Q_cholmod| / max |Q| = {:.2e} "
          "({} columns per solve)\n",
          columns_s, relative_difference(Qc, Q), kColumnsPerBlock);
      fmt::print(
          "  mumps direct      Q in {:7.3f} s, max |Q - Q_cholmod| / max |Q| = {:.2e}, "
          "interior solve K^-1 f: max |u - u_cholmod| / max |u| = {:.2e}\n",
          direct_s, relative_difference(direct.Q, Q), u0_difference);
    }
    PetscSynchronizedPrintf(PETSC_COMM_WORLD, "  rank %d: peak resident memory %.0f MiB\n", rank,
                            peak_mib);
    PetscSynchronizedFlush(PETSC_COMM_WORLD, PETSC_STDOUT);
    // As a test (tests/CMakeLists.txt, label mpi): both ways must give fricon's Q.
    const double worst = std::max({relative_difference(Qs, Q), relative_difference(Qc, Q),
                                   relative_difference(direct.Q, Q), u0_difference});
    if (rank == 0 && worst > kAgreement) {
      std::fprintf(stderr, "petsc_schur_probe: Q or u0 differs from fricon's\n");
      status = 1;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "petsc_schur_probe (rank %d): %s\n", rank, e.what());
    status = 1;
  }
  PetscFinalize();
  return status;
}

}  // namespace

int main(int argc, char** argv) {
  // Read before PETSc starts, so that --help and a bad argument end every rank at once.
  CLI::App app{
      "Two ways of forming the paper brick's Q = B K^-1 B^T with MUMPS through PETSc on P ranks, "
      "against fricon's own (run it with mpirun -n P).",
      "petsc_schur_probe"};
  int n = 8;
  bool try_solve = false;
  app.add_option("n", n, "Mesh parameter n of the paper's brick")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  app.add_flag("--try-solve", try_solve,
               "Try MatSolve with the Schur factor on several ranks too (hangs with PETSc 3.18)");
  return fricon::bench::run_main(app, argc, argv, [&] { return probe(argc, argv, n, try_solve); });
}
