// libFuzzer target for the reader of fricon's dual files, "fricon dual v1"
// (src/fricon/io/dual_dump.cpp, docs/dual-format.md), which other programs may write and
// `fricon dual solve` reads.
//
// The input is the content of the file. Whatever the bytes, read_dual must either return a dual
// problem or throw fricon::InputError; any other exception (it escapes and aborts), a crash, a
// hang, a sanitizer report, or a returned problem that breaks the reader's contract (m >= 1
// patches; h of 3m, radius and patch_area of m entries; Q 3m x 3m with a positive diagonal; all
// finite) is a finding.
//
// Build and run: fuzz/run.sh [SECONDS] dual_fuzz; see docs/fuzzing.md.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "fricon/core/error.hpp"
#include "fricon/io/dual_dump.hpp"
#include "input_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static fricon::fuzz::InputFile file;
  try {
    const fricon::qp::DualProblem d = fricon::io::read_dual(file.write(data, size));
    const auto m = d.radius.size(), n = 3 * m;
    const bool sizes =
        m >= 1 && d.h.size() == n && d.patch_area.size() == m && d.Q.rows() == n && d.Q.cols() == n;
    if (!sizes || !d.Q.allFinite() || !d.h.allFinite() || !d.radius.allFinite() ||
        !d.patch_area.allFinite() || !(d.Q.diagonal().array() > 0.0).all()) {
      std::fprintf(stderr, "read_dual returned a problem that breaks its contract (m = %td)\n",
                   static_cast<std::ptrdiff_t>(m));
      std::abort();
    }
  } catch (const fricon::InputError&) {
    // The expected way to refuse bad input.
  }
  return 0;
}
