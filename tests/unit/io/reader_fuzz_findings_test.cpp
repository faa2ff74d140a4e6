// io: what fuzzing the readers of other programs' files found (docs/fuzzing.md, "Findings so
// far"), one reproducer each. Every input must be refused with an InputError that names what is
// wrong; before the fixes each one escaped as another exception (an internal error, exit code 3),
// allocated gigabytes, or read or wrote outside an array (under AddressSanitizer: a report).

#include <filesystem>
#include <functional>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/fixtures.hpp"
#include "fricon/core/error.hpp"
#include "fricon/io/dual_dump.hpp"
#include "fricon/io/siconos_dat.hpp"

namespace fricon::io {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

class ReaderFuzzFinding : public test::TempDirTest {
 protected:
  /// The message of the InputError that `read` throws on a file holding `text`, or what else
  /// happened.
  std::string error_of(const std::function<void(const fs::path&)>& read,
                       const std::string& text) const {
    try {
      const std::string message = read_error("input", text, read);
      return message.empty() ? "read without an error" : message;
    } catch (const std::exception& e) {
      return std::string("not an InputError: ") + e.what();
    }
  }
  std::string siconos(const std::string& text) const {
    return error_of([](const fs::path& p) { (void)read_siconos_dat(p); }, text);
  }
  std::string dual(const std::string& text) const {
    return error_of([](const fs::path& p) { (void)read_dual(p); }, text);
  }
};

// The header of a local problem of 2 contacts with W 6 x 6 in sparse-block storage (1), as
// fuzz/seeds/siconos_dat/local-sbm.dat: dimension, contacts, storage, rows, columns, blocks.
const std::string kSbmHeader = "3\n2\n1\n6\n6\n2\n";

// Counts of the sparse-block header sized vectors before anything was read: a negative one threw
// std::length_error, a large one allocated 8 bytes per unit (32 GiB here, std::bad_alloc).
TEST_F(ReaderFuzzFinding, SiconosBlockCountsAreBoundedByTheFile) {
  EXPECT_THAT(siconos(kSbmHeader + "-1\n2\n3 6\n"), HasSubstr("-1 x 2 block rows and columns"));
  EXPECT_THAT(siconos(kSbmHeader + "2\n4294967296\n3 6\n"),
              HasSubstr("4294967296 tokens needed, 0 left"));
  EXPECT_THAT(siconos(kSbmHeader + "2\n2\n3 6\n3 6\n4294967296\n"),
              HasSubstr("the file ends where block count"));
}

// Block indices of the file were looked up with .at(), whose std::out_of_range escaped. Block 0
// (rows and columns 0..3) is valid; the second block, or its column, is not.
TEST_F(ReaderFuzzFinding, SiconosBlockIndicesOutOfRangeAreInputErrors) {
  const std::string sizes = "2\n2\n3 6\n3 6\n3\n2\n", block0 = "0\n1 0 0 0 1 0 0 0 1\n";
  EXPECT_THAT(siconos(kSbmHeader + sizes + "0 1 2\n0 2\n" + block0),
              HasSubstr("block column index 2 out of [0, 2)"));
  EXPECT_THAT(siconos(kSbmHeader + sizes + "0 1 5\n0 1\n" + block0 + "1\n1 0 0 0 1 0 0 0 1\n"),
              HasSubstr("the block row pointers run from 0 to 5, not 0 to 2"));
  EXPECT_THAT(siconos(kSbmHeader + sizes + "0 1 2\n0 -9223372036854775808\n" + block0),
              HasSubstr("block column index -9223372036854775808 out of [0, 2)"));
}

// Found by siconos_dat_fuzz on the token reader (docs/fuzzing.md): a row pointer past the number
// of blocks (0 4 2 for 2 blocks) was followed, reading past the blocks' columns
// (AddressSanitizer: heap-buffer-overflow), before the next pointer showed the decrease.
TEST_F(ReaderFuzzFinding, SiconosRowPointersPastTheBlocksAreRefused) {
  const std::string sizes = "2\n2\n3 6\n3 6\n3\n2\n", block0 = "0\n1 0 0 0 1 0 0 0 1\n";
  EXPECT_THAT(siconos(kSbmHeader + sizes + "0 4 2\n0 1\n" + block0),
              HasSubstr("the block row pointers decrease (4 then 2)"));
}

// Found by siconos_dat_fuzz on the token reader: a sparse-block matrix with no block and
// 9223372036854775807 columns was allocated from its header (UBSan: signed overflow in Eigen).
TEST_F(ReaderFuzzFinding, SiconosEmptyMatrixLargerThanTheFileIsRefused) {
  EXPECT_THAT(siconos("3\n2\n1\n6\n9223372036854775807\n0\n"), HasSubstr("larger than the file's"));
}

// Found by siconos_dat_fuzz: 3074457345618258603 contacts made 3 n_contacts overflow (UBSan).
TEST_F(ReaderFuzzFinding, SiconosContactsBeyondTheFileAreRefused) {
  EXPECT_THAT(siconos("3\n3074457345618258603\n0\n3\n3\n3 3\n1 0 0 0 1 0 0 0 1\n"),
              HasSubstr("3074457345618258603 contacts, more than the file's"));
}

// A block whose cumulative sizes reach past the matrix (columns 0..5 of a 4 x 4 M) was written
// outside Eigen's arrays by setFromTriplets (AddressSanitizer: heap-buffer-overflow).
TEST_F(ReaderFuzzFinding, SiconosBlocksOutsideTheMatrixAreRefused) {
  std::string text = "3\n1\n1\n4\n4\n1\n1\n1\n4\n5\n2\n1\n0 1\n0\n0\n";
  for (int k = 0; k < 20; ++k)
    text += k % 5 == k / 5 ? "2 " : "0 ";
  text += "\n0\n4\n3\n4 3\n1 0 0 0 0 1 0 0 0 0 1 0\n1 2 3 4\n0 0 0\n0.5\n";
  EXPECT_THAT(siconos(text),
              HasSubstr("the cumulative block column sizes end at 5, not at its size 4"));
}

// A matrix was allocated from its header: 100000 x 100000 dense is 80 GB (std::bad_alloc). Its
// sizes are now bounded by the file's bytes, and so are its entries.
TEST_F(ReaderFuzzFinding, SiconosDenseMatrixLargerThanTheFileIsRefused) {
  EXPECT_THAT(siconos("3\n1\n0\n100000\n100000\n100000 100000\n1\n"),
              HasSubstr("is 100000 x 100000, larger than the file's 8 numbers"));
  EXPECT_THAT(siconos("3\n1\n0\n1000\n1000\n1000 1000\n1\n" + std::string(1000, '\n')),
              HasSubstr("is 1000 x 1000, larger than the file's 8 numbers"));
}

// A global problem's M that is not square was factorized all the same, out of bounds
// (AddressSanitizer: heap-buffer-overflow in SimplicialLDLT).
TEST_F(ReaderFuzzFinding, SiconosGlobalProblemWithNonSquareMIsRefused) {
  std::string text = "3\n1\n0\n4\n5\n4 5\n";
  for (int k = 0; k < 20; ++k)
    text += k % 5 == k / 5 ? "2 " : "0 ";
  text += "\n0\n4\n3\n4 3\n1 0 0 0 0 1 0 0 0 0 1 0\n1 2 3 4\n0 0 0\n0.5\n";
  EXPECT_THAT(siconos(text), HasSubstr("M is 4 x 5, not square"));
}

// 200 kB declaring 20000 patches made the reader allocate Q, 60000 x 60000 (29 GB), before
// reading a row of it (std::bad_alloc). Found by review while writing dual_fuzz: the fuzzer's
// inputs (16 kB at most) cannot declare enough rows.
TEST_F(ReaderFuzzFinding, DualFileTooShortForQIsRefusedBeforeAllocatingIt) {
  constexpr int kPatches = 20000;
  std::string text = std::string(kDualMagic) + "\nsource big\npatches " + std::to_string(kPatches) +
                     "\npatch_data " + std::to_string(kPatches) + " 5\n";
  for (int i = 0; i < kPatches; ++i)
    text += "1 0 0 1 1\n";
  text += "Q 60000 60000\n1 0 0\nend\n";
  EXPECT_THAT(dual(text), HasSubstr("the 60000 rows of Q need at least 7200000000 bytes"));
}

}  // namespace
}  // namespace fricon::io
