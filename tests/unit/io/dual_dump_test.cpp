// io: the "fricon dual v1" file of a Tresca step's dual problem (src/fricon/io/dual_dump.hpp).

#include "fricon/io/dual_dump.hpp"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/fixtures.hpp"
#include "fricon/core/error.hpp"

namespace fricon::io {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

/// A fresh folder per test (dir_), removed at the end.
class DualDump : public test::TempDirTest {
 protected:
  fs::path write_text(const std::string& name, const std::string& text) const {
    return dir_.write(name, text);
  }

  /// The message of the InputError that reading `text` throws, or "" if it does not throw.
  std::string error_of(const std::string& text) const {
    return read_error("bad.dual", text, [](const fs::path& p) { (void)read_dual(p); });
  }
};

/// Doubles with every kind of bit pattern a dump can meet: random magnitudes over the whole
/// exponent range, signs, subnormals, -0.0 and values with 17 significant digits.
double random_double(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> kind(0, 9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_int_distribution<int> e(-300, 300);
  switch (kind(rng)) {
    case 0:
      return std::numeric_limits<double>::denorm_min() * static_cast<double>(rng() % 1000 + 1);
    case 1:
      return -0.0;
    case 2: {  // an arbitrary finite bit pattern
      double v = 0.0;
      do {
        const std::uint64_t bits = rng();
        std::memcpy(&v, &bits, sizeof v);
      } while (!std::isfinite(v));
      return v;
    }
    default:
      return u(rng) * std::pow(10.0, e(rng));
  }
}

/// |v|, or 1 if v is a zero.
double positive(double v) {
  return v != 0.0 ? std::abs(v) : 1.0;
}

qp::DualProblem random_snapshot(Index m, unsigned seed) {
  std::mt19937_64 rng(seed);
  qp::DualProblem d;
  const Index n = 3 * m;
  d.Q.resize(n, n);
  for (Index i = 0; i < n; ++i) {
    for (Index j = 0; j < i; ++j)
      d.Q(i, j) = d.Q(j, i) = random_double(rng);
    d.Q(i, i) = positive(random_double(rng));  // the reader checks only the diagonal's sign
  }
  d.h.resize(n);
  for (Index i = 0; i < n; ++i)
    d.h(i) = random_double(rng);
  d.radius.resize(m);
  d.patch_area.resize(m);
  for (Index i = 0; i < m; ++i) {
    d.radius(i) = std::abs(random_double(rng));
    d.patch_area(i) = positive(random_double(rng));
  }
  d.source = "brick n=4 \\ \"quoted\"\nsecond line\r and a tab\t, ünïcode";
  return d;
}

bool bitwise_equal(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

TEST_F(DualDump, RoundTripIsBitwiseExact) {
  for (const Index m : {1, 2, 7}) {
    const auto d = random_snapshot(m, 1234u + static_cast<unsigned>(m));
    const fs::path p = dir_.path() / ("round_trip_" + std::to_string(m) + ".dual");
    write_dual(p, d);
    EXPECT_FALSE(fs::exists(p.string() + ".tmp"));
    const auto r = read_dual(p);
    EXPECT_TRUE(bitwise_equal(r.Q, d.Q)) << "m = " << m;
    EXPECT_TRUE(bitwise_equal(r.h, d.h)) << "m = " << m;
    EXPECT_TRUE(bitwise_equal(r.radius, d.radius)) << "m = " << m;
    EXPECT_TRUE(bitwise_equal(r.patch_area, d.patch_area)) << "m = " << m;
    EXPECT_EQ(r.source, d.source);
  }
}

TEST_F(DualDump, EmptySourceRoundTrips) {
  auto d = random_snapshot(1, 7);
  d.source.clear();
  write_dual(dir_.path() / "empty.dual", d);
  EXPECT_EQ(read_dual(dir_.path() / "empty.dual").source, "");
}

// A tiny file written by hand: comments, blank lines, CRLF, tabs, a '+' sign and exponents.
TEST_F(DualDump, ReadsHandWrittenFile) {
  const std::string text =
      "# fricon dual v1\n"
      "# two patches, written by hand\n"
      "\n"
      "source hand\\\\made\\nfile\n"
      "patches 2\r\n"
      "patch_data 2 5\n"
      "1.5e-7  0 -2e-8   6e6 0.25\n"
      "# a comment between rows\n"
      "\t3e-7 1e-9 +0.0\t0   0.125\n"
      "Q 6 6\n"
      "4e-12 1e-13 0 0 0 0\n"
      "1e-13 3e-12 0 0 0 0\n"
      "0 0 3e-12 0 0 0\n"
      "0 0 0 4e-12 0 -1e-13\n"
      "0 0 0 0 3e-12 0\n"
      "0 0 0 -1e-13 0 3e-12\n"
      "end\n"
      "# trailing comment\n";
  const auto d = read_dual(write_text("hand.dual", text));
  EXPECT_EQ(d.source, "hand\\made\nfile");
  ASSERT_EQ(d.h.size(), 6);
  EXPECT_EQ(d.h(0), 1.5e-7);
  EXPECT_EQ(d.h(1), 0.0);
  EXPECT_EQ(d.h(2), -2e-8);
  EXPECT_EQ(d.h(3), 3e-7);
  EXPECT_EQ(d.h(4), 1e-9);
  EXPECT_EQ(d.h(5), 0.0);
  ASSERT_EQ(d.radius.size(), 2);
  EXPECT_EQ(d.radius(0), 6e6);
  EXPECT_EQ(d.radius(1), 0.0);
  EXPECT_EQ(d.patch_area(0), 0.25);
  EXPECT_EQ(d.patch_area(1), 0.125);
  ASSERT_EQ(d.Q.rows(), 6);
  ASSERT_EQ(d.Q.cols(), 6);
  EXPECT_EQ(d.Q(0, 0), 4e-12);
  EXPECT_EQ(d.Q(0, 1), 1e-13);
  EXPECT_EQ(d.Q(1, 0), 1e-13);
  EXPECT_EQ(d.Q(3, 5), -1e-13);
  EXPECT_EQ(d.Q(5, 5), 3e-12);
}

// The file the writer produces is the documented layout, line by line.
TEST_F(DualDump, WrittenLayout) {
  qp::DualProblem d;
  d.Q = Eigen::MatrixXd::Identity(3, 3) * 2e-12;
  d.Q(0, 1) = d.Q(1, 0) = 0.1;
  d.h = Eigen::Vector3d(1e-7, -0.0, 3.0);
  d.radius = Eigen::VectorXd::Constant(1, 6e6);
  d.patch_area = Eigen::VectorXd::Constant(1, 0.0625);
  d.source = "x.toml";
  write_dual(dir_.path() / "layout.dual", d);
  std::ifstream f(dir_.path() / "layout.dual");
  std::vector<std::string> lines;
  for (std::string l; std::getline(f, l);)
    if (!l.empty() && (l[0] != '#' || lines.empty())) lines.push_back(l);
  const std::vector<std::string> expected = {"# fricon dual v1",
                                             "source x.toml",
                                             "patches 1",
                                             "patch_data 1 5",
                                             "1e-07 -0 3 6000000 0.0625",
                                             "Q 3 3",
                                             "2e-12 0.1 0",
                                             "0.1 2e-12 0",
                                             "0 0 2e-12",
                                             "end"};
  EXPECT_EQ(lines, expected);
}

TEST_F(DualDump, WriterRejectsInconsistentSizes) {
  auto d = random_snapshot(2, 3);
  d.h.resize(5);
  EXPECT_THROW(write_dual(dir_.path() / "bad.dual", d), Error);
  d = random_snapshot(2, 3);
  d.Q(0, 0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(write_dual(dir_.path() / "bad.dual", d), Error);
  EXPECT_FALSE(fs::exists(dir_.path() / "bad.dual"));
}

// ------------------------------------------------------------------------------------------
// Malformed files: every error names the file and the line.

const std::string kHeader = "# fricon dual v1\nsource t\npatches 1\npatch_data 1 5\n";
const std::string kRow = "1e-7 0 0 6e6 0.25\n";
const std::string kQ = "Q 3 3\n2e-12 0 0\n0 2e-12 0\n0 0 2e-12\n";

TEST_F(DualDump, ValidBaseFileReads) {
  EXPECT_EQ(error_of(kHeader + kRow + kQ + "end\n"), "");
}

TEST_F(DualDump, RejectsMalformedFilesNamingFileAndLine) {
  struct Case {
    std::string text, line, what;
  };
  const std::vector<Case> cases = {
      {"", ":1:", "line 1 must be '# fricon dual v1'"},
      {"# fricon dual v2\n", ":1:", "line 1 must be"},
      {"# fricon dual v1\npatches 1\n", ":2:", "expected 'source'"},
      {"# fricon dual v1\nsource a\\x\n", ":2:", "unknown escape"},
      {"# fricon dual v1\nsource t\n", ":3:", "unexpected end of file, expected 'patches'"},
      {"# fricon dual v1\nsource t\npatches two\n", ":3:", "is not a whole number"},
      {"# fricon dual v1\nsource t\npatches 0\n", ":3:", "must be >= 1"},
      {"# fricon dual v1\nsource t\npatches 1\npatch_data 2 5\n", ":4:", "expected 1"},
      {"# fricon dual v1\nsource t\npatches 1\npatchdata 1 5\n", ":4:", "expected 'patch_data'"},
      {kHeader + "1e-7 0 0 6e6\n", ":5:", "expected 5 numbers, found 4"},
      {kHeader + "1e-7 0 zero 6e6 0.25\n", ":5:", "'zero' is not a number"},
      {kHeader + "1e-7 0 0x1 6e6 0.25\n", ":5:", "'0x1' is not a number"},
      {kHeader + "1e-7 0 nan 6e6 0.25\n", ":5:", "not finite"},
      {kHeader + "1e-7 0 1e999 6e6 0.25\n", ":5:", "out of the range"},
      {kHeader + "1e-7 0 0 -6e6 0.25\n", ":5:", "radius -6000000 is negative"},
      {kHeader + "1e-7 0 0 6e6 0\n", ":5:", "area 0 is not positive"},
      {kHeader + kRow + "Q 3 4\n", ":6:", "expected 3"},
      {kHeader + kRow + "Q 3 3\n2e-12 0 0\n0 2e-12\n", ":8:", "Q row 2: expected 3 numbers"},
      {kHeader + kRow + "Q 3 3\n2e-12 0 0\n0 -2e-12 0\n0 0 2e-12\nend\n",
       ":8:", "diagonal entry -2e-12 is not positive"},
      {kHeader + kRow + "Q 3 3\n2e-12 0 0\n# c\n\n1e-13 2e-12 0\n0 0 2e-12\nend\n",
       ":10:", "Q is not symmetric: Q(2,1) = 1e-13 but Q(1,2) = 0 on line 7"},
      {kHeader + kRow + "Q 3 3\n2e-12 0 0\n0 2e-12 0\n", ":9:", "expected Q row 3"},
      {kHeader + kRow + kQ, ":10:", "unexpected end of file, expected 'end'"},
      {kHeader + kRow + kQ + "0 0 0\n", ":10:", "expected 'end' after the 3 rows of Q"},
      {kHeader + kRow + kQ + "end\n\n1\n", ":12:", "text after 'end'"},
  };
  for (const auto& c : cases) {
    const std::string msg = error_of(c.text);
    EXPECT_THAT(msg, HasSubstr("bad.dual" + c.line)) << c.text;
    EXPECT_THAT(msg, HasSubstr(c.what)) << c.text;
  }
}

TEST_F(DualDump, MissingFileIsAnInputError) {
  try {
    (void)read_dual(dir_.path() / "missing.dual");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("missing.dual"));
  }
}

}  // namespace
}  // namespace fricon::io
