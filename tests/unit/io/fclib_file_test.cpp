// io: FCLIB files written by libfclib's own writer (fclib_write_local / fclib_write_global) and
// read back by fricon (issue 23, defect 2). The matrices are not symmetric, or not square, so
// that a reader that swapped rows and columns would be caught: W non-symmetric in the three
// storages FCLIB has (triplets, compressed columns, compressed rows), a tall H in triplets, and
// the same H with rows and columns swapped, which must be refused naming the file. Where
// ../shared holds FCLIB's global test problems, their triplet arrays are checked to keep the row
// in i (docs/dual-format.md, "FCLIB's triplet layout").
#include "fricon/io/fclib_file.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Dense>

extern "C" {
#include <fclib.h>
}

#include "common/fixtures.hpp"
#include "fricon/core/error.hpp"

namespace fricon::io {
namespace {

namespace fs = std::filesystem;

// An fclib_matrix owning its arrays.
struct Matrix {
  std::vector<int> p, i;
  std::vector<double> x;
  fclib_matrix m{};
  Matrix() = default;
  Matrix(const Matrix&) = delete;
  void finish(int rows, int cols, int nz) {
    m.m = rows;
    m.n = cols;
    m.nz = nz;
    m.nzmax = static_cast<int>(x.size());
    m.p = p.data();
    m.i = i.data();
    m.x = x.data();
  }
};

enum class Storage { Triplets, Columns, Rows, SwappedTriplets };

// A as FCLIB stores it. Triplets: p the column and i the row of each entry (CSparse's layout, the
// one FCLIB's files use); SwappedTriplets: p the row and i the column (fclib.h's comment).
void store(const MatrixXd& A, Storage storage, Matrix& out) {
  const int rows = static_cast<int>(A.rows()), cols = static_cast<int>(A.cols());
  if (storage == Storage::Triplets || storage == Storage::SwappedTriplets) {
    for (int j = 0; j < cols; ++j)
      for (int r = 0; r < rows; ++r)
        if (A(r, j) != 0.0) {
          const bool swap = storage == Storage::SwappedTriplets;
          out.p.push_back(swap ? r : j);
          out.i.push_back(swap ? j : r);
          out.x.push_back(A(r, j));
        }
    out.finish(rows, cols, static_cast<int>(out.x.size()));
    return;
  }
  const bool by_column = storage == Storage::Columns;
  const int outer = by_column ? cols : rows, inner = by_column ? rows : cols;
  out.p.push_back(0);
  for (int o = 0; o < outer; ++o) {
    for (int n = 0; n < inner; ++n) {
      const double v = by_column ? A(n, o) : A(o, n);
      if (v != 0.0) {
        out.i.push_back(n);
        out.x.push_back(v);
      }
    }
    out.p.push_back(static_cast<int>(out.x.size()));
  }
  out.finish(rows, cols, by_column ? -1 : -2);
}

class FclibFile : public test::TempDirTest {
 protected:
  /// A path in this test's folder where no file is (FCLIB's writers refuse to add a second
  /// problem to a file).
  fs::path fresh(const std::string& name) const {
    fs::remove(dir_.path() / name);
    return dir_.path() / name;
  }
};

// Two contacts, W not symmetric: W(0, 1) = 0.3 but W(1, 0) = 0, and so on.
MatrixXd nonsymmetric_W() {
  MatrixXd W(6, 6);
  W << 2.0, 0.3, 0.0, 0.1, 0.0, 0.0,  //
      0.0, 1.5, 0.2, 0.0, 0.0, 0.0,   //
      0.1, 0.0, 1.0, 0.0, 0.0, 0.4,   //
      0.0, 0.0, 0.0, 3.0, 0.5, 0.0,   //
      0.2, 0.0, 0.0, 0.0, 2.5, 0.0,   //
      0.0, 0.0, 0.0, 0.6, 0.0, 1.2;
  return W;
}

TEST_F(FclibFile, NonSymmetricWReadsBackAsWrittenInAllThreeStorages) {
  const MatrixXd W = nonsymmetric_W();
  VectorXd q(6), mu(2);
  q << -1.0, 0.5, 0.25, -2.0, 0.0, 1.0;
  mu << 0.3, 0.4;
  for (const Storage storage : {Storage::Triplets, Storage::Columns, Storage::Rows}) {
    Matrix w;
    store(W, storage, w);
    fclib_local local{};
    local.spacedim = 3;
    local.W = &w.m;
    local.q = q.data();
    local.mu = mu.data();
    const fs::path file = fresh("local.hdf5");
    ASSERT_EQ(fclib_write_local(&local, file.c_str()), 1);
    const qp::LocalProblem p = read_fclib(file);
    EXPECT_EQ(MatrixXd(p.W), W) << "storage " << static_cast<int>(storage);
    EXPECT_EQ(p.q, q);
    EXPECT_EQ(p.mu, mu);
    // fricon's own writer (compressed columns) keeps it too.
    const fs::path again = fresh("again.hdf5");
    write_fclib_solution(again, p, VectorXd::Zero(6), p.q);
    EXPECT_EQ(MatrixXd(read_fclib(again).W), W);
  }
}

// FCLIB's merit of the exact solution of a non-symmetric problem is zero with W as read, and
// clearly not with its transpose: the merit sees the orientation fricon hands it.
TEST_F(FclibFile, MeritSeesTheOrientationOfW) {
  MatrixXd W = MatrixXd::Identity(3, 3);
  W(0, 1) = 0.2;  // W r = -q with q = (-1, -0.1, 0): r = (0.98, 0.1, 0), inside the cone
  qp::LocalProblem p;
  p.W = W.sparseView();
  p.q = (VectorXd(3) << -1.0, -0.1, 0.0).finished();
  p.mu = VectorXd::Constant(1, 0.5);
  const VectorXd r = (VectorXd(3) << 0.98, 0.1, 0.0).finished();
  EXPECT_LE(fclib_merit(p, r, p.W * r + p.q), 1e-15);
  qp::LocalProblem t = p;
  t.W = SparseMatrix(p.W.transpose());
  EXPECT_GE(fclib_merit(t, r, t.W * r + t.q), 1e-2);
}

// A global problem with H tall (8 dofs, 2 contacts) in triplets: reduced to W = H^T M^-1 H and
// q = H^T M^-1 f + w, checked against a dense computation.
struct Global {
  MatrixXd M{8, 8}, H{8, 6};
  VectorXd f{8}, w{6}, mu{2};
  Global() {
    M.setZero();
    for (int k = 0; k < 8; ++k) {
      M(k, k) = 2.0 + k;
      if (k + 1 < 8) M(k, k + 1) = M(k + 1, k) = 0.5;
    }
    for (int r = 0; r < 8; ++r)
      for (int c = 0; c < 6; ++c)
        H(r, c) = (r + 2 * c) % 5 == 0 ? 1.0 + 0.1 * r : ((r * c) % 7 == 3 ? -0.5 : 0.0);
    f << 1, -2, 0.5, 3, 0, -1, 2, 0.25;
    w << 0.1, 0.2, -0.3, 0, 0.5, -0.1;
    mu << 0.3, 0.5;
  }
  fs::path write(const fs::path& file, Storage h_storage) {
    Matrix m, h;
    store(M, Storage::Triplets, m);
    store(H, h_storage, h);
    fclib_global g{};
    g.spacedim = 3;
    g.M = &m.m;
    g.H = &h.m;
    g.f = f.data();
    g.w = w.data();
    g.mu = mu.data();
    EXPECT_EQ(fclib_write_global(&g, file.c_str()), 1);
    return file;
  }
};

TEST_F(FclibFile, GlobalProblemWithTallTripletHIsReduced) {
  Global g;
  const qp::LocalProblem p = read_fclib(g.write(fresh("global.hdf5"), Storage::Triplets));
  const MatrixXd W = g.H.transpose() * g.M.ldlt().solve(g.H);
  const VectorXd q = g.H.transpose() * g.M.ldlt().solve(g.f) + g.w;
  ASSERT_EQ(p.W.rows(), 6);
  EXPECT_LE((MatrixXd(p.W) - W).norm(), 1e-14 * W.norm());
  EXPECT_LE((p.q - q).norm(), 1e-14 * q.norm());
  EXPECT_EQ(p.mu, g.mu);
}

// H's rows and columns swapped in the triplets (fclib.h's comment read literally): rows reach 7
// in a matrix of 6 columns, refused naming the file, the matrix and the layout.
TEST_F(FclibFile, TripletsWithTheRowInPAreRefusedNamingTheFile) {
  Global g;
  const fs::path file = g.write(fresh("swapped.hdf5"), Storage::SwappedTriplets);
  try {
    read_fclib(file);
    FAIL() << "read a tall H with swapped triplets";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(file.string()), std::string::npos) << what;
    EXPECT_NE(what.find("matrix H (8 x 6"), std::string::npos) << what;
    EXPECT_NE(what.find("out of range"), std::string::npos) << what;
  }
}

// FCLIB's own global test problems (Siconos' data in ../shared): H is tall and in triplets, and
// i reaches beyond its number of columns, so i holds the row and p the column.
TEST(FclibThirdPartyFiles, TripletsKeepTheRowInI) {
  const fs::path dir = test::shared_data("siconos-fc3d");
  int checked = 0;
  for (const char* name : {"Box_Stacks-i0122-82-5.hdf5", "Spheres-i099-356-679.hdf5"}) {
    const fs::path file = dir / name;
    if (!fs::exists(file)) continue;
    fclib_global* g = fclib_read_global(file.c_str());
    ASSERT_NE(g, nullptr) << file;
    const fclib_matrix& H = *g->H;
    ASSERT_GE(H.nz, 0) << name << ": H is not in triplets";
    ASSERT_GT(H.m, H.n) << name;
    const int max_i = *std::max_element(H.i, H.i + H.nz);
    const int max_p = *std::max_element(H.p, H.p + H.nz);
    EXPECT_GE(max_i, H.n) << name << ": i does not exceed the column count";
    EXPECT_LT(max_p, H.n) << name;
    std::printf("%s: H is %d x %d in %d triplets, max i = %d, max p = %d\n", name, H.m, H.n, H.nz,
                max_i, max_p);
    fclib_delete_global(g);  // frees the members only
    std::free(g);
    ++checked;
  }
  if (checked == 0) GTEST_SKIP() << dir << " is absent";
}

}  // namespace
}  // namespace fricon::io
