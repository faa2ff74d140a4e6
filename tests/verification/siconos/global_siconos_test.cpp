// The global frictional contact problems of ../shared (Siconos' GFC3D_*.dat and FCLIB's
// Box_Stacks) read by fricon and by Siconos 4.4, reduced to local form by each and solved by each
// (issue 23, defects 2 and 3). Siconos reads the .dat files with its own reader
// (globalFrictionContact_new_from_filename). Debian builds Siconos without FCLIB, so its FCLIB
// reader is not there to call: the FCLIB file's arrays are read by libfclib and handed to Siconos
// as its FCLIB reader (from_fclib_global) hands them, fclib's triplet p as CSparse's p (the
// column). Checked:
//   - W = H^T M^-1 H and q = H^T M^-1 f + w: fricon's against Siconos' own reduction
//     (globalFrictionContact_reformulation_FrictionContact), to 1e-10 relative;
//   - fricon's local solve against Siconos' global solver (gfc3d ADMM, which works on M and H,
//     no reduction): Siconos' reactions solve fricon's local problem (FCLIB merit <= 1e-8), and
//     velocities and reactions agree to 1e-6 relative (only the normal reactions where W is
//     singular and the tangential ones are not unique).
// Siconos' matrices are made dense: its sparse solves go through MUMPS, whose sequential build
// (Siconos') and parallel build (fricon's PETSc backend) cannot share one process.
// A file that is absent is skipped (GTEST_SKIP: CTest reports it skipped).
#include <gtest/gtest.h>

#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Eigenvalues>
#include "FrictionContactProblem.h"
#include "Friction_cst.h"
#include "GlobalFrictionContactProblem.h"
#include "NonSmoothDrivers.h"
#include "NumericsMatrix.h"
#include "NumericsSparseMatrix.h"
#include "SolverOptions.h"

#include "common/fixtures.hpp"
#include "fricon/driver/local_solve.hpp"
#include "fricon/io/fclib_file.hpp"
#include "fricon/io/local_problem_file.hpp"

extern "C" {
#include <fclib.h>
}

using namespace fricon;
namespace fs = std::filesystem;

namespace {

constexpr double kReductionTolerance = 1e-10;  // relative, W and q
constexpr double kReactionTolerance = 1e-6;    // relative, fricon's r against Siconos'
constexpr double kMeritTolerance = 1e-8;       // FCLIB's merit of Siconos' reactions
constexpr double kSiconosTolerance = 1e-12;    // Siconos' own error
constexpr int kSiconosIterations = 10000;
constexpr double kDefinite = 1e-10;  // W counts as definite above this lambda_min / lambda_max

fs::path shared_file(const std::string& name) {
  return test::shared_data("siconos-fc3d") / name;
}

struct GlobalDeleter {
  void operator()(GlobalFrictionContactProblem* p) const { globalFrictionContact_free(p); }
};
using Global = std::unique_ptr<GlobalFrictionContactProblem, GlobalDeleter>;

// An FCLIB matrix as a Siconos sparse (triplet) matrix, read as Siconos' from_fclib_global reads
// it: it copies fclib's p into CSparse's triplet p, which CSparse takes as the column (cs_entry
// stores the column of an entry there), and i into i, the row.
NumericsMatrix* siconos_matrix(const fclib_matrix& a) {
  EXPECT_GE(a.nz, 0) << "the FCLIB files checked here store M and H as triplets";
  NumericsMatrix* A = NM_create(NM_SPARSE, a.m, a.n);
  NM_triplet_alloc(A, a.nz);
  for (int k = 0; k < a.nz; ++k)
    NM_entry(A, a.i[k], a.p[k], a.x[k]);
  return A;
}

double* copy(const double* x, int n) {
  auto* y = static_cast<double*>(std::malloc(sizeof(double) * static_cast<size_t>(n)));
  std::copy(x, x + n, y);
  return y;
}

// The file read as Siconos reads it: a .dat file by Siconos' own reader; an FCLIB file's arrays,
// read by libfclib, as Siconos' FCLIB reader takes them.
Global read_as_siconos_reads(const fs::path& file) {
  if (file.extension() == ".dat")
    return Global(globalFrictionContact_new_from_filename(file.c_str()));
  fclib_global* g = fclib_read_global(file.c_str());
  Global p(globalFrictionContactProblem_new());
  p->dimension = g->spacedim;
  p->numberOfContacts = g->H->n / g->spacedim;
  p->M = siconos_matrix(*g->M);
  p->H = siconos_matrix(*g->H);
  p->q = copy(g->f, g->M->m);
  p->b = copy(g->w, g->H->n);
  p->mu = copy(g->mu, p->numberOfContacts);
  fclib_delete_global(g);
  std::free(g);
  return p;
}

// A Siconos matrix replaced by its dense copy (Siconos' NM_to_dense).
NumericsMatrix* to_dense(NumericsMatrix* A) {
  NumericsMatrix* D = NM_create(NM_DENSE, A->size0, A->size1);
  EXPECT_EQ(NM_to_dense(A, D), 0);
  NM_free(A);
  return D;
}

// The file as a Siconos global problem (M v = H r + q, u = H^T v + b), M and H dense.
Global siconos_read(const fs::path& file) {
  Global p = read_as_siconos_reads(file);
  if (p) {
    p->M = to_dense(p->M);
    p->H = to_dense(p->H);
  }
  return p;
}

// A Siconos matrix as a dense one, column by column (y = A e_j), whatever its storage.
MatrixXd dense(NumericsMatrix* A) {
  MatrixXd D(A->size0, A->size1);
  VectorXd e = VectorXd::Zero(A->size1), y(A->size0);
  for (int j = 0; j < A->size1; ++j) {
    e(j) = 1.0;
    NM_gemv(1.0, A, e.data(), 0.0, y.data());
    D.col(j) = y;
    e(j) = 0.0;
  }
  return D;
}

double relative(const MatrixXd& a, const MatrixXd& b) {
  return (a - b).norm() / b.norm();
}

class GlobalAgainstSiconos : public ::testing::TestWithParam<const char*> {};

TEST_P(GlobalAgainstSiconos, SameLocalProblemAndSameReactions) {
  const fs::path file = shared_file(GetParam());
  if (!fs::exists(file)) GTEST_SKIP() << file << " is absent";
  const qp::LocalProblem ours = io::read_local_problem(file);

  // @sect: Siconos' reduction (it factorizes M in place: a problem of its own).
  {
    Global g = siconos_read(file);
    ASSERT_TRUE(g) << file;
    FrictionContactProblem* local = globalFrictionContact_reformulation_FrictionContact(g.get());
    ASSERT_NE(local, nullptr);
    const MatrixXd W = dense(local->M);
    const VectorXd q = Eigen::Map<const VectorXd>(local->q, W.rows());
    ASSERT_EQ(W.rows(), ours.W.rows());
    EXPECT_LE(relative(MatrixXd(ours.W), W), kReductionTolerance) << file;
    EXPECT_LE(relative(ours.q, q), kReductionTolerance) << file;
    frictionContactProblem_free(local);
  }

  // @sect: Siconos' global solver against fricon's local solve.
  Global g = siconos_read(file);
  const int n = g->M->size0, m = g->H->size1;
  VectorXd r = VectorXd::Zero(m), u = VectorXd::Zero(m), v = VectorXd::Zero(n);
  SolverOptions* o = solver_options_create(SICONOS_GLOBAL_FRICTION_3D_ADMM);
  o->dparam[SICONOS_DPARAM_TOL] = kSiconosTolerance;
  o->iparam[SICONOS_IPARAM_MAX_ITER] = kSiconosIterations;
  const int info = gfc3d_driver(g.get(), r.data(), u.data(), v.data(), o);
  solver_options_delete(o);
  EXPECT_EQ(info, 0) << "Siconos' gfc3d ADMM did not converge on " << file;

  driver::LocalSolveOptions so;
  so.merit = [&ours](const VectorXd& x, const VectorXd& y) { return io::fclib_merit(ours, x, y); };
  const driver::LocalSolution s = driver::solve_local(ours, so);
  ASSERT_TRUE(s.solved) << s.reason;
  // Siconos' global answer solves fricon's local problem, with the same velocities u = H^T v + w.
  EXPECT_LE(io::fclib_merit(ours, r, ours.W * r + ours.q), kMeritTolerance) << file;
  EXPECT_LE(relative(s.u, u), kReactionTolerance) << file;
  // The reactions are unique only where W is definite (Box_Stacks' W is singular: a box resting
  // on several contacts leaves their tangential reactions free).
  const Eigen::SelfAdjointEigenSolver<MatrixXd> eig(MatrixXd(ours.W), Eigen::EigenvaluesOnly);
  if (eig.eigenvalues().minCoeff() > kDefinite * eig.eigenvalues().maxCoeff()) {
    EXPECT_LE(relative(s.r, r), kReactionTolerance)
        << file << "\nfricon  " << s.r.transpose() << "\nSiconos " << r.transpose();
  } else {
    VectorXd rn(m / 3), sn(m / 3);
    for (int a = 0; a < m / 3; ++a) {
      rn(a) = r(3 * a);
      sn(a) = s.r(3 * a);
    }
    EXPECT_LE(relative(sn, rn), kReactionTolerance) << file << ": normal reactions";
  }
}

INSTANTIATE_TEST_SUITE_P(SharedData, GlobalAgainstSiconos,
                         ::testing::Values("GFC3D_OneContact.dat", "GFC3D_TwoRods1.dat",
                                           "Box_Stacks-i0122-82-5.hdf5"),
                         [](const auto& param) {
                           std::string name = param.param;
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

}  // namespace
