#include "fricon/io/siconos_dat.hpp"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <Eigen/SparseCholesky>

#include "fricon/core/error.hpp"

namespace fricon::io {

namespace {

// What goes wrong while reading the file one way (local or global), without the file's name.
struct Mismatch {
  std::string what;
};

struct Token {
  std::string text;
  long line = 0;
};

// The file's whitespace-separated tokens, each with its line, read one at a time; integers and
// numbers must be whole tokens ("1.5" is not an integer, "1e3x" not a number).
class Tokens {
 public:
  explicit Tokens(const std::filesystem::path& path) {
    std::ifstream in(path);
    if (!in) throw InputError(fmt::format("{}: cannot open the problem file", path.string()));
    std::string line;
    for (long n = 1; std::getline(in, line); ++n) {
      size_t i = 0;
      while (true) {
        i = line.find_first_not_of(" \t\r\f\v", i);
        if (i == std::string::npos) break;
        const size_t j = std::min(line.find_first_of(" \t\r\f\v", i), line.size());
        tokens_.push_back({line.substr(i, j - i), n});
        i = j;
      }
    }
  }
  long integer(const std::string& what) {
    const Token& t = next(what);
    long v = 0;
    const auto [end, ec] = std::from_chars(t.text.data(), t.text.data() + t.text.size(), v);
    if (ec != std::errc() || end != t.text.data() + t.text.size())
      throw Mismatch{
          fmt::format("line {}: expected an integer ({}), found '{}'", t.line, what, t.text)};
    return v;
  }
  Real real(const std::string& what) {
    const Token& t = next(what);
    char* end = nullptr;
    const Real v = std::strtod(t.text.c_str(), &end);
    if (end != t.text.c_str() + t.text.size() || !std::isfinite(v))
      throw Mismatch{
          fmt::format("line {}: expected a finite number ({}), found '{}'", t.line, what, t.text)};
    return v;
  }
  VectorXd reals(Index n, const std::string& what) {
    require(n, what);
    VectorXd v(n);
    for (Index k = 0; k < n; ++k)
      v(k) = real(what);
    return v;
  }
  // Before a block of n tokens is allocated: the file must still hold them.
  void require(long n, const std::string& what) const {
    if (n < 0 || static_cast<size_t>(n) > remaining())
      throw Mismatch{fmt::format("the file ends before {}: {} {} needed, {} left", what, n,
                                 n == 1 ? "token" : "tokens", remaining())};
  }
  size_t position() const { return next_; }
  void seek(size_t position) { next_ = position; }
  size_t remaining() const { return tokens_.size() - next_; }
  size_t total() const { return tokens_.size(); }
  const Token& peek() const { return tokens_[next_]; }

 private:
  const Token& next(const std::string& what) {
    if (next_ >= tokens_.size())
      throw Mismatch{fmt::format("the file ends where {} was expected", what)};
    return tokens_[next_++];
  }
  std::vector<Token> tokens_;
  size_t next_ = 0;
};

// A sparse-block matrix (Siconos' SBM_write_in_file): the number of blocks; if not zero, the
// numbers of block rows and block columns, the cumulative block sizes in each direction, the
// counts of row pointers and of blocks, the row pointers, the blocks' columns, then each block (its
// number, then its values column by column). Its structure is checked against the sizes.
SparseMatrix read_sparse_block(Tokens& t, const std::string& name, Index rows, Index cols) {
  const auto in = [&name](const char* what) { return fmt::format("{} of matrix {}", what, name); };
  const long n_blocks = t.integer(in("number of blocks"));
  if (n_blocks == 0) return SparseMatrix(rows, cols);
  const long n_row_blocks = t.integer(in("block rows")),
             n_col_blocks = t.integer(in("block columns"));
  if (n_blocks < 0 || n_row_blocks <= 0 || n_col_blocks <= 0)
    throw Mismatch{fmt::format("matrix {}: {} blocks in {} x {} block rows and columns", name,
                               n_blocks, n_row_blocks, n_col_blocks)};
  const auto cumulative = [&](long count, Index total, const char* what) {
    t.require(count, in(what));
    std::vector<long> end(static_cast<size_t>(count));
    long before = 0;
    for (auto& e : end) {
      e = t.integer(in(what));
      if (e <= before)
        throw Mismatch{
            fmt::format("matrix {}: the {} do not increase ({} after {})", name, what, e, before)};
      before = e;
    }
    if (before != total)
      throw Mismatch{fmt::format("matrix {}: the {} end at {}, not at its size {}", name, what,
                                 before, total)};
    return end;
  };
  const std::vector<long> row_end = cumulative(n_row_blocks, rows, "cumulative block row sizes");
  const std::vector<long> col_end = cumulative(n_col_blocks, cols, "cumulative block column sizes");
  const long filled1 = t.integer(in("row pointer count")), filled2 = t.integer(in("block count"));
  if (filled1 != n_row_blocks + 1 || filled2 != n_blocks)
    throw Mismatch{
        fmt::format("matrix {}: {} row pointers and {} blocks, expected {} (block rows + 1) and {}",
                    name, filled1, filled2, n_row_blocks + 1, n_blocks)};
  t.require(filled1 + filled2, in("block row pointers and block columns"));
  std::vector<long> row_ptr(static_cast<size_t>(filled1)), block_col(static_cast<size_t>(filled2));
  for (auto& e : row_ptr)
    e = t.integer(in("block row pointer"));
  for (auto& e : block_col) {
    e = t.integer(in("block column index"));
    if (e < 0 || e >= n_col_blocks)
      throw Mismatch{
          fmt::format("matrix {}: block column index {} out of [0, {})", name, e, n_col_blocks)};
  }
  if (row_ptr.front() != 0 || row_ptr.back() != n_blocks)
    throw Mismatch{fmt::format("matrix {}: the block row pointers run from {} to {}, not 0 to {}",
                               name, row_ptr.front(), row_ptr.back(), n_blocks)};
  // All pointers in order before any is used (one past n_blocks would read past block_col).
  for (size_t br = 0; br + 1 < row_ptr.size(); ++br)
    if (row_ptr[br + 1] < row_ptr[br])
      throw Mismatch{fmt::format("matrix {}: the block row pointers decrease ({} then {})", name,
                                 row_ptr[br], row_ptr[br + 1])};
  std::vector<Eigen::Triplet<Real, SparseIndex>> entries;
  for (size_t br = 0; br + 1 < row_ptr.size(); ++br) {
    for (long b = row_ptr[br]; b < row_ptr[br + 1]; ++b) {
      const auto bc = static_cast<size_t>(block_col[static_cast<size_t>(b)]);
      const long r0 = br == 0 ? 0 : row_end[br - 1], c0 = bc == 0 ? 0 : col_end[bc - 1];
      const long nr = row_end[br] - r0, nc = col_end[bc] - c0;
      if (const long number = t.integer(in("block number")); number != b)
        throw Mismatch{
            fmt::format("matrix {}: block number {} where block {} was expected", name, number, b)};
      for (long j = 0; j < nc; ++j)
        for (long i = 0; i < nr; ++i)
          entries.emplace_back(r0 + i, c0 + j, t.real(in("block entry")));
    }
  }
  SparseMatrix A(rows, cols);
  A.setFromTriplets(entries.begin(), entries.end());
  return A;
}

// A NumericsMatrix (NM_write_in_file): storage, sizes, then the dense values (the sizes again,
// then column-major) or the sparse blocks.
SparseMatrix read_matrix(Tokens& t, const std::string& name) {
  const auto in = [&name](const char* what) { return fmt::format("{} of matrix {}", what, name); };
  const long storage = t.integer(in("storage"));
  const long rows = t.integer(in("rows")), cols = t.integer(in("columns"));
  if (rows <= 0 || cols <= 0) throw Mismatch{fmt::format("matrix {} is {} x {}", name, rows, cols)};
  // Each dimension is the size of a vector the file holds too (q, f, w): an empty sparse matrix
  // of a size beyond the file's tokens would be allocated from its header alone.
  if (static_cast<size_t>(rows) > t.total() || static_cast<size_t>(cols) > t.total())
    throw Mismatch{fmt::format("matrix {} is {} x {}, larger than the file's {} numbers", name,
                               rows, cols, t.total())};
  if (storage == 0) {
    const long r = t.integer(in("dense rows")), c = t.integer(in("dense columns"));
    if (r != rows || c != cols)
      throw Mismatch{fmt::format("matrix {} is {} x {} but its dense part says {} x {}", name, rows,
                                 cols, r, c)};
    t.require(rows * cols, in("dense entries"));
    MatrixXd A(rows, cols);
    for (long j = 0; j < cols; ++j)
      for (long i = 0; i < rows; ++i)
        A(i, j) = t.real(in("dense entry"));
    return A.sparseView();
  }
  if (storage == 1) return read_sparse_block(t, name, rows, cols);
  throw Mismatch{
      fmt::format("matrix {} has storage {}; fricon reads dense (0) and sparse-block (1) matrices",
                  name, storage)};
}

// After mu: nothing, or the one flag 0 or 1 that Siconos wrote there until 2010 (its problem's
// "isComplete", since dropped and ignored by its readers; docs/dual-format.md). Anything else is
// left over: the file is not what its sizes say.
void expect_end(Tokens& t) {
  if (t.remaining() == 1 && (t.peek().text == "0" || t.peek().text == "1"))
    t.seek(t.position() + 1);
  if (t.remaining() == 0) return;
  throw Mismatch{fmt::format("{} {} left over after mu, from line {} ('{}')", t.remaining(),
                             t.remaining() == 1 ? "token" : "tokens", t.peek().line,
                             t.peek().text)};
}

// The rest of a local problem after its W: q, mu, the end.
qp::LocalProblem read_local_rest(Tokens& t, const SparseMatrix& W, long nc) {
  if (W.rows() != 3 * nc || W.cols() != 3 * nc)
    throw Mismatch{
        fmt::format("W is {} x {}, not 3 n_contacts = {} square", W.rows(), W.cols(), 3 * nc)};
  qp::LocalProblem p;
  p.W = W;
  p.q = t.reals(3 * nc, "q (3 n_contacts numbers)");
  p.mu = t.reals(nc, "mu (n_contacts numbers)");
  expect_end(t);
  return p;
}

// The rest of a global problem after its M: H, q, b, mu, the end; reduced to local form,
// W = H^T M^-1 H and q_local = H^T M^-1 q + b (theory.md §5.6).
qp::LocalProblem read_global_rest(Tokens& t, const SparseMatrix& M, long nc) {
  if (M.rows() != M.cols())
    throw Mismatch{fmt::format("M is {} x {}, not square", M.rows(), M.cols())};
  const SparseMatrix H = read_matrix(t, "H");
  if (H.rows() != M.rows() || H.cols() != 3 * nc)
    throw Mismatch{fmt::format("H is {} x {}, not n x 3 n_contacts = {} x {}", H.rows(), H.cols(),
                               M.rows(), 3 * nc)};
  const VectorXd q = t.reals(M.rows(), "q (n numbers)");
  const VectorXd b = t.reals(3 * nc, "b (3 n_contacts numbers)");
  qp::LocalProblem p;
  p.mu = t.reals(nc, "mu (n_contacts numbers)");
  expect_end(t);
  const Eigen::SimplicialLDLT<SparseMatrix> ldlt(M);
  if (ldlt.info() != Eigen::Success || (ldlt.vectorD().array() <= 0.0).any())
    throw Mismatch{fmt::format("M ({} x {}) is not positive definite", M.rows(), M.cols())};
  const MatrixXd MinvH = ldlt.solve(MatrixXd(H));
  const MatrixXd W = MatrixXd(H.transpose()) * MinvH;
  p.W = (0.5 * (W + W.transpose())).sparseView();
  p.q = H.transpose() * ldlt.solve(q) + b;
  return p;
}

// One reading of the tokens after the first matrix: the problem, or why not.
struct Attempt {
  std::optional<qp::LocalProblem> problem;
  std::string why_not;
};

template <class Read>
Attempt attempt(Tokens& t, size_t from, Read read) {
  t.seek(from);
  try {
    return {read(), {}};
  } catch (const Mismatch& m) {
    return {std::nullopt, m.what};
  }
}

}  // namespace

qp::LocalProblem read_siconos_dat(const std::filesystem::path& path) {
  Tokens t(path);
  const auto fail = [&path](const std::string& what) {
    return InputError(fmt::format("{}: Siconos .dat file: {}", path.string(), what));
  };
  try {
    const long dim = t.integer("the dimension");
    const long nc = t.integer("the number of contacts");
    if (dim != 3 || nc <= 0)
      throw fail(fmt::format("dimension {} with {} contacts; fricon solves 3D problems", dim, nc));
    // Each contact has its coefficient (and 3 entries of q) in the file.
    if (static_cast<size_t>(nc) > t.total())
      throw fail(fmt::format("{} contacts, more than the file's {} numbers", nc, t.total()));
    const SparseMatrix first = read_matrix(t, "W (local) or M (global)");
    // Local (W, q, mu) or global (M, H, q, b, mu): the file says which only by how its tokens
    // add up, so both readings are tried to the end of the file; exactly one must fit.
    const size_t after_first = t.position();
    const Attempt local = attempt(t, after_first, [&] { return read_local_rest(t, first, nc); });
    const Attempt global = attempt(t, after_first, [&] { return read_global_rest(t, first, nc); });
    if (local.problem && global.problem)
      throw fail("ambiguous: it reads completely both as a local and as a global problem");
    if (!local.problem && !global.problem)
      throw fail(
          fmt::format("neither a local problem (W, q, mu: {}) nor a global one (M, H, q, "
                      "b, mu: {})",
                      local.why_not, global.why_not));
    qp::LocalProblem p = local.problem ? *local.problem : *global.problem;
    p.source = path.string();
    return p;
  } catch (const Mismatch& m) {
    throw fail(m.what);
  }
}

}  // namespace fricon::io
