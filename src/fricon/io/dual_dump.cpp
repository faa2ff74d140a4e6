#include "fricon/io/dual_dump.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string_view>
#include <system_error>
#include <vector>

#include <fmt/format.h>

#include "fricon/core/error.hpp"
#include "fricon/io/atomic_file.hpp"

namespace fricon::io {

namespace {

// Q counts as symmetric when |Q_ij - Q_ji| <= kSymmetryTolerance * max |Q_kl|.
constexpr double kSymmetryTolerance = 1e-8;

std::string escape(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\r':
        out += "\\r";
        break;
      default:
        out += c;
    }
  }
  return out;
}

using Buffer = fmt::memory_buffer;

void append_row(Buffer& buf, const double* values, Index n) {
  for (Index j = 0; j < n; ++j) {
    if (j > 0) buf.push_back(' ');
    fmt::format_to(std::back_inserter(buf), "{}", values[j]);
  }
  buf.push_back('\n');
}

// ------------------------------------------------------------------------------------------
// Reading: the significant lines (not blank, not a comment) with their 1-based line numbers.

class Lines {
 public:
  Lines(std::string text, std::string file) : text_(std::move(text)), file_(std::move(file)) {}

  const std::string& file() const { return file_; }
  /// Line number of the line returned last.
  int line() const { return line_; }
  /// Bytes of the text after the line returned last.
  std::size_t remaining() const { return text_.size() - pos_; }

  /// The first physical line (the magic line), without its line break.
  std::string_view first() {
    line_ = 1;
    return take_physical();
  }

  /// The next significant line; false at the end of the file.
  bool next(std::string_view& out) {
    while (pos_ < text_.size()) {
      ++line_;
      std::string_view l = take_physical();
      if (l.empty() || l.front() == '#') continue;
      if (l.find_first_not_of(" \t") == std::string_view::npos) continue;
      out = l;
      return true;
    }
    ++line_;  // errors at the end of the file name the line after the last one
    return false;
  }

  /// The next significant line, or an error saying what was expected.
  std::string_view expect(std::string_view what) {
    std::string_view l;
    if (!next(l)) fail(fmt::format("unexpected end of file, expected {}", what));
    return l;
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(fmt::format("{}:{}: {}", file_, line_, what));
  }

 private:
  std::string_view take_physical() {
    const std::size_t end = std::min(text_.find('\n', pos_), text_.size());
    std::string_view l(text_.data() + pos_, end - pos_);
    pos_ = end < text_.size() ? end + 1 : end;
    if (!l.empty() && l.back() == '\r') l.remove_suffix(1);  // CRLF files
    return l;
  }

  std::string text_;
  std::string file_;
  std::size_t pos_ = 0;
  int line_ = 0;
};

/// Splits a line into tokens separated by spaces or tabs.
std::vector<std::string_view> tokens(std::string_view l) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (true) {
    i = l.find_first_not_of(" \t", i);
    if (i == std::string_view::npos) break;
    std::size_t j = l.find_first_of(" \t", i);
    if (j == std::string_view::npos) j = l.size();
    out.push_back(l.substr(i, j - i));
    i = j;
  }
  return out;
}

double parse_number(const Lines& in, std::string_view tok) {
  std::string_view t = tok;
  if (!t.empty() && t.front() == '+') t.remove_prefix(1);
  double v = 0.0;
  const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  if (ec == std::errc::result_out_of_range)
    in.fail(fmt::format("number '{}' is out of the range of a double", tok));
  if (ec != std::errc() || ptr != t.data() + t.size() || t.empty())
    in.fail(fmt::format("'{}' is not a number", tok));
  if (!std::isfinite(v)) in.fail(fmt::format("number '{}' is not finite", tok));
  return v;
}

Index parse_count(const Lines& in, std::string_view tok, std::string_view what) {
  long long v = 0;
  const auto [ptr, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), v);
  if (ec != std::errc() || ptr != tok.data() + tok.size() || tok.empty())
    in.fail(fmt::format("{} '{}' is not a whole number", what, tok));
  return static_cast<Index>(v);
}

/// A header line "<keyword> <count>..." with the given number of counts, which must match
/// `expected` (if given, one per count).
void expect_header(Lines& in, std::string_view keyword, const std::vector<Index>& expected) {
  const std::string_view l = in.expect(fmt::format("'{}'", keyword));
  const auto t = tokens(l);
  if (t.empty() || t[0] != keyword)
    in.fail(fmt::format("expected '{}', found '{}'", keyword, t.empty() ? l : t[0]));
  if (t.size() != expected.size() + 1)
    in.fail(
        fmt::format("'{}' takes {} count(s), found {}", keyword, expected.size(), t.size() - 1));
  for (std::size_t k = 0; k < expected.size(); ++k) {
    const Index v = parse_count(in, t[k + 1], fmt::format("count of '{}'", keyword));
    if (v != expected[k])
      in.fail(fmt::format("'{}': count {} is {}, expected {}", keyword, k + 1, v, expected[k]));
  }
}

/// One data row of exactly n numbers into out[0..n).
void read_row(Lines& in, Index n, std::string_view what, double* out) {
  const std::string_view l = in.expect(std::string(what));
  const auto t = tokens(l);
  if (static_cast<Index>(t.size()) != n)
    in.fail(fmt::format("{}: expected {} numbers, found {}", what, n, t.size()));
  for (Index j = 0; j < n; ++j)
    out[j] = parse_number(in, t[static_cast<std::size_t>(j)]);
}

std::string unescape(const Lines& in, std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] != '\\') {
      out += s[i];
      continue;
    }
    if (i + 1 == s.size()) in.fail("source: a backslash ends the line (write \\\\ for one)");
    const char c = s[++i];
    if (c == '\\') {
      out += '\\';
    } else if (c == 'n') {
      out += '\n';
    } else if (c == 'r') {
      out += '\r';
    } else {
      in.fail(fmt::format("source: unknown escape '\\{}' (only \\\\, \\n, \\r)", c));
    }
  }
  return out;
}

}  // namespace

void write_dual(const std::filesystem::path& path, const qp::DualProblem& d) {
  const Index m = d.radius.size();
  FRICON_CHECK(m >= 1, "a dual problem needs at least one patch");
  FRICON_CHECK(d.h.size() == 3 * m, "h has " << d.h.size() << " entries, expected " << 3 * m);
  FRICON_CHECK(d.patch_area.size() == m,
               "patch_area has " << d.patch_area.size() << " entries, expected " << m);
  FRICON_CHECK(d.Q.rows() == 3 * m && d.Q.cols() == 3 * m, "Q is " << d.Q.rows() << " x "
                                                                   << d.Q.cols() << ", expected "
                                                                   << 3 * m << " x " << 3 * m);
  FRICON_CHECK(
      d.Q.allFinite() && d.h.allFinite() && d.radius.allFinite() && d.patch_area.allFinite(),
      "the dual problem has non-finite values");

  const Index n = 3 * m;
  Buffer buf;
  auto out = std::back_inserter(buf);
  fmt::format_to(out, "{}\n", kDualMagic);
  fmt::format_to(out,
                 "# minimise 1/2 l^T Q l - l^T h over l = (l_n, l_t1, l_t2) per patch,\n"
                 "# l_n >= 0 and ||(l_t1, l_t2)|| <= radius; Q [m^3/Pa], h [m^3], radius [Pa], "
                 "area [m^2], l [Pa].\n"
                 "# Layout and the FCLIB/Siconos mapping (W = Q, q = -h): docs/dual-format.md\n");
  fmt::format_to(out, "source {}\n", escape(d.source));
  fmt::format_to(out, "patches {}\n", m);
  fmt::format_to(out, "# h_n h_t1 h_t2 radius area\n");
  fmt::format_to(out, "patch_data {} 5\n", m);
  for (Index i = 0; i < m; ++i) {
    const double row[5] = {d.h(3 * i), d.h(3 * i + 1), d.h(3 * i + 2), d.radius(i),
                           d.patch_area(i)};
    append_row(buf, row, 5);
  }
  fmt::format_to(out, "# Q, full, row-major\n");
  fmt::format_to(out, "Q {} {}\n", n, n);
  std::vector<double> row(static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i) {
    for (Index j = 0; j < n; ++j)
      row[static_cast<std::size_t>(j)] = d.Q(i, j);
    append_row(buf, row.data(), n);
  }
  fmt::format_to(out, "end\n");

  write_atomically(path, [&buf](std::ostream& os) {
    os.write(buf.data(), static_cast<std::streamsize>(buf.size()));
  });
}

qp::DualProblem read_dual(const std::filesystem::path& path) {
  const std::string file = path.string();
  std::string text;
  {
    std::ifstream f(path, std::ios::binary);
    if (!f) throw InputError(fmt::format("{}: cannot open the dual file", file));
    std::ostringstream ss;
    ss << f.rdbuf();
    if (f.bad()) throw InputError(fmt::format("{}: reading failed", file));
    text = std::move(ss).str();
  }
  Lines in(std::move(text), file);

  const std::string_view magic = in.first();
  if (magic != kDualMagic) in.fail(fmt::format("not a dual file: line 1 must be '{}'", kDualMagic));

  qp::DualProblem d;

  // source <text>: everything after "source " verbatim (then unescaped).
  {
    const std::string_view l = in.expect("'source'");
    const std::string_view key = "source";
    if (l.substr(0, key.size()) != key || (l.size() > key.size() && l[key.size()] != ' '))
      in.fail(fmt::format("expected 'source', found '{}'", tokens(l).front()));
    d.source = unescape(in, l.size() > key.size() ? l.substr(key.size() + 1) : "");
  }

  // patches <m>
  Index m = 0;
  {
    const std::string_view l = in.expect("'patches'");
    const auto t = tokens(l);
    if (t[0] != "patches") in.fail(fmt::format("expected 'patches', found '{}'", t[0]));
    if (t.size() != 2) in.fail("'patches' takes one count");
    m = parse_count(in, t[1], "number of patches");
    if (m < 1) in.fail(fmt::format("number of patches {} must be >= 1", m));
    // Q alone needs 9 m^2 numbers of at least two characters each: reject absurd counts
    // before allocating.
    if (m > 1000000) in.fail(fmt::format("number of patches {} is implausibly large", m));
  }
  const Index n = 3 * m;

  expect_header(in, "patch_data", {m, 5});
  d.h.resize(n);
  d.radius.resize(m);
  d.patch_area.resize(m);
  for (Index i = 0; i < m; ++i) {
    double row[5];
    read_row(in, 5, fmt::format("patch_data row {}", i + 1), row);
    d.h.segment<3>(3 * i) << row[0], row[1], row[2];
    if (row[3] < 0.0) in.fail(fmt::format("patch {}: radius {} is negative", i + 1, row[3]));
    if (!(row[4] > 0.0)) in.fail(fmt::format("patch {}: area {} is not positive", i + 1, row[4]));
    d.radius(i) = row[3];
    d.patch_area(i) = row[4];
  }

  expect_header(in, "Q", {n, n});
  // Each of Q's n rows of n numbers takes at least 2n bytes (a digit and a blank or line break
  // per number): a file too short for them is refused before Q is allocated (issue 23: 200 kB
  // declaring 20000 patches allocated 29 GB, std::bad_alloc).
  if (in.remaining() / static_cast<std::size_t>(n) < 2 * static_cast<std::size_t>(n))
    in.fail(fmt::format("the {} rows of Q need at least {} bytes, the file has {} left", n,
                        2 * n * n, in.remaining()));
  d.Q.resize(n, n);
  std::vector<int> q_line(static_cast<std::size_t>(n));  // file line of each row of Q
  {
    std::vector<double> row(static_cast<std::size_t>(n));
    for (Index i = 0; i < n; ++i) {
      read_row(in, n, fmt::format("Q row {}", i + 1), row.data());
      q_line[static_cast<std::size_t>(i)] = in.line();
      if (!(row[static_cast<std::size_t>(i)] > 0.0))
        in.fail(fmt::format("Q row {}: diagonal entry {} is not positive", i + 1,
                            row[static_cast<std::size_t>(i)]));
      for (Index j = 0; j < n; ++j)
        d.Q(i, j) = row[static_cast<std::size_t>(j)];
    }
  }

  {
    const std::string_view l = in.expect("'end'");
    if (tokens(l).size() != 1 || tokens(l)[0] != "end")
      in.fail(fmt::format("expected 'end' after the {} rows of Q, found '{}'", n, l));
    std::string_view extra;
    if (in.next(extra)) in.fail("text after 'end'");
  }

  // Symmetry, checked once the whole matrix is read; the message names the line of the later
  // row of the offending pair and the line of the earlier one.
  const double scale = d.Q.cwiseAbs().maxCoeff();
  for (Index i = 1; i < n; ++i)
    for (Index j = 0; j < i; ++j)
      if (std::abs(d.Q(i, j) - d.Q(j, i)) > kSymmetryTolerance * scale)
        throw InputError(fmt::format(
            "{}:{}: Q is not symmetric: Q({},{}) = {} but Q({},{}) = {} on line {} (tolerance "
            "{} max|Q|)",
            file, q_line[static_cast<std::size_t>(i)], i + 1, j + 1, d.Q(i, j), j + 1, i + 1,
            d.Q(j, i), q_line[static_cast<std::size_t>(j)], kSymmetryTolerance));
  return d;
}

}  // namespace fricon::io
