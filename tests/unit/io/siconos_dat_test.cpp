// Siconos' .dat format: the same local problem written dense and sparse-block reads back to the
// same W, q and mu, and a global problem is reduced to W = H^T M^-1 H, q = H^T M^-1 q_g + b
// (checked here against a dense computation).
#include "fricon/io/siconos_dat.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

#include <Eigen/Dense>

#include "common/fixtures.hpp"
#include "fricon/core/error.hpp"

namespace fricon::io {
namespace {

class SiconosDat : public test::TempDirTest {
 protected:
  std::filesystem::path write(const std::string& name, const std::string& text) {
    return dir_.write(name, text);
  }
};

// W = diag(blocks A, B) of two contacts, written dense (column-major) and sparse-block.
TEST_F(SiconosDat, DenseAndSparseBlockGiveTheSameProblem) {
  Eigen::Matrix<Real, 6, 6> W = Eigen::Matrix<Real, 6, 6>::Zero();
  W.block<3, 3>(0, 0) << 2, 0.1, 0, 0.1, 2, 0.2, 0, 0.2, 3;
  W.block<3, 3>(3, 3) << 4, 0, 0.5, 0, 1, 0, 0.5, 0, 2;
  std::ostringstream dense, sbm;
  dense << "3\n2\n0\n6\n6\n6\t6\n";
  for (int j = 0; j < 6; ++j)
    for (int i = 0; i < 6; ++i)
      dense << W(i, j) << " ";
  sbm << "3\n2\n1\n6\n6\n2\n2\n2\n3 6\n3 6\n3\n2\n0 1 2\n0 1\n";
  for (int b = 0; b < 2; ++b) {
    sbm << b << "\n";
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i)
        sbm << W(3 * b + i, 3 * b + j) << "\n";
  }
  const std::string tail = "\n-1 0.5 0.25 -2 0 1\n0.3 0.4\n0\n";
  const auto a = read_siconos_dat(write("dense.dat", dense.str() + tail));
  const auto b = read_siconos_dat(write("sbm.dat", sbm.str() + tail));
  EXPECT_EQ(MatrixXd(a.W), MatrixXd(W));
  EXPECT_EQ(MatrixXd(b.W), MatrixXd(W));
  EXPECT_EQ(a.q, b.q);
  EXPECT_EQ(a.q(0), -1.0);
  EXPECT_EQ(b.mu, (VectorXd(2) << 0.3, 0.4).finished());
}

TEST_F(SiconosDat, GlobalProblemIsReducedToLocalForm) {
  // M (4 x 4, SPD), H (4 x 3: one contact), q_g, b, mu.
  MatrixXd M(4, 4), H(4, 3);
  M << 4, 1, 0, 0, 1, 3, 0.5, 0, 0, 0.5, 2, 0.1, 0, 0, 0.1, 5;
  H << 1, 0, 0.2, 0, 1, 0, 0.3, 0, 1, 0.1, 0.2, 0.3;
  const VectorXd qg = (VectorXd(4) << 1, -2, 0.5, 3).finished();
  const VectorXd b = (VectorXd(3) << 0.1, 0.2, -0.3).finished();
  std::ostringstream s;
  s.precision(17);
  s << "3\n1\n0\n4\n4\n4\t4\n";
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i)
      s << M(i, j) << " ";
  s << "\n0\n4\n3\n4\t3\n";
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i)
      s << H(i, j) << " ";
  s << "\n" << qg.transpose() << "\n" << b.transpose() << "\n0.5\n";
  const auto p = read_siconos_dat(write("global.dat", s.str()));
  const MatrixXd W = H.transpose() * M.ldlt().solve(H);
  EXPECT_LT((MatrixXd(p.W) - W).norm(), 1e-14 * W.norm());
  EXPECT_LT((p.q - (H.transpose() * M.ldlt().solve(qg) + b)).norm(), 1e-14 * p.q.norm());
  EXPECT_EQ(p.mu(0), 0.5);
}

TEST_F(SiconosDat, TruncatedOrNonThreeDimensionalFilesAreRefused) {
  EXPECT_THROW(read_siconos_dat(write("t.dat", "3\n2\n0\n6\n6\n6\t6\n1 2 3\n")), InputError);
  EXPECT_THROW(read_siconos_dat(write("two.dat", "2\n1\n0\n2\n2\n2\t2\n1 0 0 1\n1 1\n0.1\n")),
               InputError);
  EXPECT_THROW(read_siconos_dat(write("csc.dat", "3\n1\n2\n3\n3\n")), InputError);
}

}  // namespace
}  // namespace fricon::io
