#include "fricon/io/fclib_file.hpp"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <vector>

#include <fmt/format.h>
#include <Eigen/SparseCholesky>

#include <hdf5.h>
extern "C" {
#include <fclib.h>
}

#include "fricon/core/error.hpp"

namespace fricon::io {

namespace {

// M of a global problem counts as symmetric when max|M - M^T| <= this times max|M|.
constexpr Real kMassSymmetryTolerance = 1e-12;

// fclib_delete_local / fclib_delete_global free the members of a problem (its info too), not the
// problem itself, which fclib_read_local / fclib_read_global allocated.
struct LocalDeleter {
  void operator()(fclib_local* p) const {
    fclib_delete_local(p);
    std::free(p);
  }
};
struct GlobalDeleter {
  void operator()(fclib_global* p) const {
    fclib_delete_global(p);
    std::free(p);
  }
};

// An FCLIB matrix (compressed columns, compressed rows or triplets) as a sparse matrix, named
// `name` in messages. Compressed forms are as fclib.h says: p the m + 1 row (nz = -2) or n + 1
// column (nz = -1) pointers, i the column or row indices. For triplets (nz >= 0) fclib.h's comment
// says that p holds row indices; the files and the codes that write them say the opposite, and
// fricon follows them: p holds the COLUMN and i the ROW of each entry, CSparse's triplet layout
// (fclib_matrix is CSparse's struct, fclib casts one to the other). The evidence is in
// docs/dual-format.md ("FCLIB's triplet layout"): the tall H of FCLIB's global test problems has
// i up to 389 with only 246 columns, and Siconos writes and reads FCLIB triplets as CSparse ones.
// Entries out of range, pointers that decrease or overrun nzmax are errors naming the file.
SparseMatrix to_sparse(const fclib_matrix& a, const char* name, const std::filesystem::path& path) {
  const auto bad = [&](const std::string& what) {
    return InputError(fmt::format("{}: FCLIB matrix {} ({} x {}, nz = {}): {}", path.string(), name,
                                  a.m, a.n, a.nz, what));
  };
  if (a.m < 0 || a.n < 0 || a.nzmax < 0 || a.nz < -2) throw bad("invalid sizes");
  std::vector<Eigen::Triplet<Real, SparseIndex>> t;
  if (a.nz >= 0) {
    if (a.nz > a.nzmax) throw bad(fmt::format("nz exceeds nzmax = {}", a.nzmax));
    for (int k = 0; k < a.nz; ++k) {
      if (a.i[k] < 0 || a.i[k] >= a.m || a.p[k] < 0 || a.p[k] >= a.n)
        throw bad(fmt::format(
            "entry {} at row i = {}, column p = {} is out of range (triplets: p the column, i the "
            "row, as CSparse and Siconos store them)",
            k, a.i[k], a.p[k]));
      t.emplace_back(a.i[k], a.p[k], a.x[k]);
    }
  } else {
    const bool by_column = a.nz == -1;
    const int outer = by_column ? a.n : a.m, inner = by_column ? a.m : a.n;
    if (a.p[0] != 0 || a.p[outer] > a.nzmax)
      throw bad(
          fmt::format("pointers run from {} to {} (nzmax = {})", a.p[0], a.p[outer], a.nzmax));
    for (int j = 0; j < outer; ++j) {
      if (a.p[j + 1] < a.p[j])
        throw bad(fmt::format("pointer {} decreases ({} then {})", j + 1, a.p[j], a.p[j + 1]));
      for (int k = a.p[j]; k < a.p[j + 1]; ++k) {
        if (a.i[k] < 0 || a.i[k] >= inner)
          throw bad(fmt::format("entry {} has index {}, out of [0, {})", k, a.i[k], inner));
        by_column ? t.emplace_back(a.i[k], j, a.x[k]) : t.emplace_back(j, a.i[k], a.x[k]);
      }
    }
  }
  for (const auto& e : t)
    if (!std::isfinite(e.value()))
      throw bad(fmt::format("entry ({}, {}) is not finite", e.row(), e.col()));
  SparseMatrix s(a.m, a.n);
  s.setFromTriplets(t.begin(), t.end());
  return s;
}

Real max_abs(const SparseMatrix& a) {
  return a.nonZeros() == 0
             ? 0.0
             : Eigen::Map<const VectorXd>(a.valuePtr(), a.nonZeros()).cwiseAbs().maxCoeff();
}

Eigen::Map<const VectorXd> vector(const double* x, Index n) {
  return Eigen::Map<const VectorXd>(x, n);
}

// Which of the given HDF5 groups the file has. FCLIB's readers end the program (or print HDF5's
// error stack) on a missing group, so the file is looked into first, with HDF5's printing off.
bool has_group(const std::filesystem::path& path, const char* group) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file < 0) return false;
  const bool found = H5Lexists(file, group, H5P_DEFAULT) > 0;
  H5Fclose(file);
  return found;
}

// The file's solution r (if any), read through FCLIB.
std::optional<VectorXd> solution_of(const std::filesystem::path& path, Index m) {
  if (!has_group(path, "/solution")) return std::nullopt;
  fclib_solution* s = fclib_read_solution(path.c_str());
  if (s == nullptr) return std::nullopt;
  std::optional<VectorXd> r;
  if (s->r != nullptr) r = vector(s->r, m);
  fclib_delete_solutions(s, 1);
  return r;
}

qp::LocalProblem from_local(const fclib_local& l, const std::filesystem::path& path) {
  if (l.spacedim != 3 || l.W == nullptr || l.q == nullptr || l.mu == nullptr)
    throw InputError(
        fmt::format("{}: FCLIB local problem: fricon solves 3D problems with W, q "
                    "and mu (spacedim is {})",
                    path.string(), l.spacedim));
  if (l.V != nullptr || l.R != nullptr)
    throw InputError(fmt::format(
        "{}: FCLIB local problem with equality constraints (V, R): not supported", path.string()));
  qp::LocalProblem p;
  p.W = to_sparse(*l.W, "W", path);
  if (p.W.rows() != p.W.cols() || p.W.rows() == 0 || p.W.rows() % 3 != 0)
    throw InputError(fmt::format(
        "{}: FCLIB local problem: W is {} x {}; fricon needs W square of size 3 n_contacts",
        path.string(), p.W.rows(), p.W.cols()));
  p.q = vector(l.q, p.W.rows());
  p.mu = vector(l.mu, p.W.rows() / 3);
  return p;
}

// W = H^T M^-1 H and q = H^T M^-1 f + w: the local form of a global problem.
qp::LocalProblem from_global(const fclib_global& g, const std::filesystem::path& path) {
  if (g.spacedim != 3 || g.M == nullptr || g.H == nullptr || g.f == nullptr || g.w == nullptr ||
      g.mu == nullptr)
    throw InputError(
        fmt::format("{}: FCLIB global problem: fricon solves 3D problems with M, H, "
                    "f, w and mu (spacedim is {})",
                    path.string(), g.spacedim));
  if (g.G != nullptr)
    throw InputError(fmt::format(
        "{}: FCLIB global problem with equality constraints (G): not supported", path.string()));
  const SparseMatrix M = to_sparse(*g.M, "M", path), H = to_sparse(*g.H, "H", path);
  if (M.rows() != M.cols() || H.rows() != M.rows() || H.cols() == 0 || H.cols() % 3 != 0)
    throw InputError(fmt::format(
        "{}: FCLIB global problem: M is {} x {} and H {} x {}; fricon needs M square (n x n) "
        "and H n x 3 n_contacts",
        path.string(), M.rows(), M.cols(), H.rows(), H.cols()));
  // The factorization reads one triangle of M: the other must agree with it.
  const Real asymmetry = max_abs(SparseMatrix(M - SparseMatrix(M.transpose()))),
             largest = max_abs(M);
  if (asymmetry > kMassSymmetryTolerance * largest)
    throw InputError(
        fmt::format("{}: FCLIB global problem: M is not symmetric (max|M - M^T| = "
                    "{:.2e}, max|M| = {:.2e})",
                    path.string(), asymmetry, largest));
  const Eigen::SimplicialLDLT<SparseMatrix> ldlt(M);
  if (ldlt.info() != Eigen::Success || (ldlt.vectorD().array() <= 0.0).any())
    throw InputError(fmt::format("{}: FCLIB global problem: M ({} x {}) is not positive definite",
                                 path.string(), M.rows(), M.cols()));
  const MatrixXd MinvH = ldlt.solve(MatrixXd(H));
  qp::LocalProblem p;
  p.W = (MatrixXd(H.transpose()) * MinvH).sparseView();
  p.W = 0.5 * (SparseMatrix(p.W) + SparseMatrix(p.W.transpose()));
  p.q = H.transpose() * ldlt.solve(VectorXd(vector(g.f, M.rows()))) + vector(g.w, H.cols());
  p.mu = vector(g.mu, H.cols() / 3);
  return p;
}

}  // namespace

bool is_hdf5_file(const std::filesystem::path& path) {
  static constexpr char kSignature[8] = {'\x89', 'H', 'D', 'F', '\r', '\n', '\x1a', '\n'};
  std::ifstream in(path, std::ios::binary);
  char head[8] = {};
  return in.read(head, 8) && std::memcmp(head, kSignature, 8) == 0;
}

qp::LocalProblem read_fclib(const std::filesystem::path& path) {
  if (!is_hdf5_file(path))
    throw InputError(fmt::format("{}: not an HDF5 (FCLIB) file", path.string()));
  qp::LocalProblem p;
  // FCLIB's readers end the program on a missing group: look into the file first.
  if (has_group(path, "/fclib_local")) {
    const std::unique_ptr<fclib_local, LocalDeleter> l{fclib_read_local(path.c_str())};
    if (!l) throw InputError(fmt::format("{}: unreadable FCLIB local problem", path.string()));
    p = from_local(*l, path);
  } else if (has_group(path, "/fclib_global")) {
    const std::unique_ptr<fclib_global, GlobalDeleter> g{fclib_read_global(path.c_str())};
    if (!g) throw InputError(fmt::format("{}: unreadable FCLIB global problem", path.string()));
    p = from_global(*g, path);
  } else {
    throw InputError(fmt::format("{}: neither an FCLIB local nor a global problem", path.string()));
  }
  p.source = path.string();
  // FCLIB reads a solution only alongside a local problem (it ends the program otherwise).
  if (has_group(path, "/fclib_local")) p.reference_r = solution_of(path, p.q.size());
  if (p.reference_r && p.reference_r->size() != p.q.size()) p.reference_r.reset();
  return p;
}

namespace {
// An fclib_local viewing the problem's data (compressed columns); owns only its index arrays.
struct LocalView {
  std::vector<int> p, i;
  std::vector<double> x, q, mu;
  fclib_matrix W{};
  fclib_local local{};
  explicit LocalView(const qp::LocalProblem& problem) {
    SparseMatrix A = problem.W;
    A.makeCompressed();
    p.assign(A.outerIndexPtr(), A.outerIndexPtr() + A.cols() + 1);
    i.assign(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros());
    x.assign(A.valuePtr(), A.valuePtr() + A.nonZeros());
    q.assign(problem.q.data(), problem.q.data() + problem.q.size());
    mu.assign(problem.mu.data(), problem.mu.data() + problem.mu.size());
    W.nzmax = static_cast<int>(x.size());
    W.m = static_cast<int>(A.rows());
    W.n = static_cast<int>(A.cols());
    W.p = p.data();
    W.i = i.data();
    W.x = x.data();
    W.nz = -1;
    local.W = &W;
    local.q = q.data();
    local.mu = mu.data();
    local.spacedim = 3;
  }
};
}  // namespace

double fclib_merit(const qp::LocalProblem& problem, const VectorXd& r, const VectorXd& u) {
  FRICON_CHECK(problem.is_coulomb(), "FCLIB's merit is defined for Coulomb problems");
  LocalView view(problem);
  std::vector<double> rr(r.data(), r.data() + r.size()), uu(u.data(), u.data() + u.size());
  fclib_solution s{};
  s.r = rr.data();
  s.u = uu.data();
  return fclib_merit_local(&view.local, MERIT_1, &s);
}

void write_fclib_solution(const std::filesystem::path& path, const qp::LocalProblem& problem,
                          const VectorXd& r, const VectorXd& u) {
  LocalView view(problem);
  std::vector<double> rr(r.data(), r.data() + r.size()), uu(u.data(), u.data() + u.size());
  fclib_solution s{};
  s.r = rr.data();
  s.u = uu.data();
  const std::filesystem::path tmp = path.string() + ".partial";
  std::error_code ec;
  std::filesystem::remove(tmp, ec);
  if (!fclib_write_local(&view.local, tmp.c_str()) || !fclib_write_solution(&s, tmp.c_str())) {
    std::filesystem::remove(tmp, ec);
    throw Error(fmt::format("{}: FCLIB could not write the solution", path.string()));
  }
  std::filesystem::rename(tmp, path);
}

}  // namespace fricon::io
