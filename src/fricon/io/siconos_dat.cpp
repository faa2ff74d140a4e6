#include "fricon/io/siconos_dat.hpp"

#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <Eigen/SparseCholesky>

#include "fricon/core/error.hpp"

namespace fricon::io {

namespace {

// The file's numbers, read one at a time, with messages that name the file and the item.
class Tokens {
 public:
  explicit Tokens(const std::filesystem::path& path) : path_(path), in_(path) {
    if (!in_) throw InputError(fmt::format("{}: cannot open the problem file", path.string()));
    in_.seekg(0, std::ios::end);
    if (const auto end = in_.tellg(); end >= 0) bytes_ = static_cast<long>(end);
    in_.seekg(0);
  }
  // A count or a size of the file (issue 23, fuzzing): every item it counts is in the file, so
  // it is at most the file's size in bytes; larger ones were allocated before being read.
  long size(const char* what) {
    const long v = integer(what);
    if (v < 0 || v > bytes_)
      throw InputError(
          fmt::format("{}: Siconos .dat file: {} {} is not between 0 and the {} bytes "
                      "of the file",
                      path_.string(), what, v, bytes_));
    return v;
  }
  long integer(const char* what) {
    long v = 0;
    if (!(in_ >> v))
      throw InputError(
          fmt::format("{}: Siconos .dat file: expected an integer ({})", path_.string(), what));
    return v;
  }
  Real real(const char* what) {
    Real v = 0;
    if (!(in_ >> v) || !std::isfinite(v))
      throw InputError(fmt::format("{}: Siconos .dat file: expected a finite number ({})",
                                   path_.string(), what));
    return v;
  }
  VectorXd reals(Index n, const char* what) {
    VectorXd v(n);
    for (Index k = 0; k < n; ++k)
      v(k) = real(what);
    return v;
  }
  const std::filesystem::path& path() const { return path_; }
  long bytes() const { return bytes_; }

 private:
  std::filesystem::path path_;
  std::ifstream in_;
  long bytes_ = std::numeric_limits<long>::max();
};

// A sparse-block matrix (Siconos' SBM_write_in_file): block counts and cumulative block sizes
// in both directions, row pointers and column indices of the blocks, then each block (its number,
// then its values column by column).
SparseMatrix read_sparse_block(Tokens& t, Index rows, Index cols) {
  const long n_blocks = t.integer("number of blocks");
  if (n_blocks == 0) return SparseMatrix(rows, cols);
  const long n_row_blocks = t.size("block rows"), n_col_blocks = t.size("block columns");
  std::vector<long> row_end(static_cast<size_t>(n_row_blocks)),
      col_end(static_cast<size_t>(n_col_blocks));
  for (auto& e : row_end)
    e = t.integer("cumulative block row size");
  for (auto& e : col_end)
    e = t.integer("cumulative block column size");
  const long filled1 = t.size("row pointer count"), filled2 = t.size("block count");
  std::vector<long> row_ptr(static_cast<size_t>(filled1)), block_col(static_cast<size_t>(filled2));
  for (auto& e : row_ptr)
    e = t.integer("block row pointer");
  for (auto& e : block_col)
    e = t.integer("block column index");
  // An index of the file into one of the arrays above (issue 23, fuzzing: .at() threw
  // std::out_of_range, an internal error).
  const auto at = [&t](const std::vector<long>& v, long k, const char* what) {
    if (k < 0 || k >= static_cast<long>(v.size()))
      throw InputError(fmt::format("{}: Siconos .dat file: {} {} is not below {}",
                                   t.path().string(), what, k, v.size()));
    return v[static_cast<size_t>(k)];
  };
  std::vector<Eigen::Triplet<Real, SparseIndex>> entries;
  for (long br = 0; br + 1 < filled1; ++br)
    for (long b = row_ptr[static_cast<size_t>(br)]; b < row_ptr[static_cast<size_t>(br) + 1]; ++b) {
      const long bc = at(block_col, b, "block");
      const long r1 = at(row_end, br, "block row"), c1 = at(col_end, bc, "block column");
      const long r0 = br == 0 ? 0 : at(row_end, br - 1, "block row");
      const long c0 = bc == 0 ? 0 : at(col_end, bc - 1, "block column");
      if (r0 < 0 || r1 < r0 || r1 > rows || c0 < 0 || c1 < c0 || c1 > cols)
        throw InputError(fmt::format(
            "{}: Siconos .dat file: block {} (rows {}..{}, columns {}..{}) is not inside the "
            "{} x {} matrix",
            t.path().string(), b, r0, r1, c0, c1, rows, cols));
      const long nr = r1 - r0, nc = c1 - c0;
      (void)t.integer("block number");
      for (long j = 0; j < nc; ++j)
        for (long i = 0; i < nr; ++i)
          entries.emplace_back(r0 + i, c0 + j, t.real("block entry"));
    }
  SparseMatrix A(rows, cols);
  A.setFromTriplets(entries.begin(), entries.end());
  return A;
}

// A NumericsMatrix: storage, sizes, then the dense values (column-major) or the sparse blocks.
SparseMatrix read_matrix(Tokens& t, const char* name) {
  const long storage = t.integer("matrix storage");
  const long rows = t.size("matrix rows"), cols = t.size("matrix columns");
  if (rows <= 0 || cols <= 0)
    throw InputError(fmt::format("{}: Siconos .dat file: matrix {} is {} x {}", t.path().string(),
                                 name, rows, cols));
  if (storage == 0) {
    (void)t.integer("dense rows");
    (void)t.integer("dense columns");
    if (cols > t.bytes() / rows)  // issue 23, fuzzing: allocated before being read
      throw InputError(
          fmt::format("{}: Siconos .dat file: matrix {} ({} x {}, dense) has more "
                      "entries than the {} bytes of the file",
                      t.path().string(), name, rows, cols, t.bytes()));
    MatrixXd A(rows, cols);
    for (long j = 0; j < cols; ++j)
      for (long i = 0; i < rows; ++i)
        A(i, j) = t.real("dense entry");
    return A.sparseView();
  }
  if (storage == 1) return read_sparse_block(t, rows, cols);
  throw InputError(
      fmt::format("{}: Siconos .dat file: matrix {} has storage {}; fricon reads "
                  "dense (0) and sparse-block (1) matrices",
                  t.path().string(), name, storage));
}

}  // namespace

qp::LocalProblem read_siconos_dat(const std::filesystem::path& path) {
  Tokens t(path);
  const long dim = t.integer("dimension");
  const long nc = t.size("number of contacts");
  if (dim != 3 || nc <= 0)
    throw InputError(
        fmt::format("{}: Siconos .dat file: dimension {} with {} contacts; fricon "
                    "solves 3D problems",
                    path.string(), dim, nc));
  qp::LocalProblem p;
  p.source = path.string();
  const SparseMatrix first = read_matrix(t, "W");
  if (first.rows() == 3 * nc && first.cols() == 3 * nc) {  // local: W, q, mu
    p.W = first;
    p.q = t.reals(3 * nc, "q");
  } else {  // global: M, H, q, b
    const SparseMatrix H = read_matrix(t, "H");
    const VectorXd q = t.reals(first.rows(), "q"), b = t.reals(H.cols(), "b");
    if (first.rows() != first.cols())  // issue 23, fuzzing: factorized out of bounds
      throw InputError(fmt::format("{}: Siconos global problem: M is {} x {}, not square",
                                   path.string(), first.rows(), first.cols()));
    const Eigen::SimplicialLDLT<SparseMatrix> ldlt(first);
    if (ldlt.info() != Eigen::Success || (ldlt.vectorD().array() <= 0.0).any() ||
        H.rows() != first.rows() || H.cols() != 3 * nc)
      throw InputError(
          fmt::format("{}: Siconos global problem: M ({} x {}) must be positive "
                      "definite and H {} x {}",
                      path.string(), first.rows(), first.cols(), first.rows(), 3 * nc));
    const MatrixXd MinvH = ldlt.solve(MatrixXd(H));
    const MatrixXd W = MatrixXd(H.transpose()) * MinvH;
    p.W = (0.5 * (W + W.transpose())).sparseView();
    p.q = H.transpose() * ldlt.solve(q) + b;
  }
  p.mu = t.reals(nc, "mu");
  return p;
}

}  // namespace fricon::io
