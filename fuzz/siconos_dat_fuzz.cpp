// libFuzzer target for the reader of Siconos' .dat files (src/fricon/io/siconos_dat.cpp), text
// that other programs write and `fricon dual solve` reads.
//
// The input is the content of the file. Whatever the bytes, read_siconos_dat must either return a
// local problem or throw fricon::InputError; any other exception (it escapes and aborts), a crash,
// a hang, a sanitizer report, or a returned problem whose sizes do not fit together (W square of
// size 3 n_contacts, q of that size, n_contacts >= 1 coefficients mu) is a finding.
//
// Build and run: fuzz/run.sh [SECONDS] siconos_dat_fuzz; see docs/fuzzing.md.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "fricon/core/error.hpp"
#include "fricon/io/siconos_dat.hpp"
#include "input_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static fricon::fuzz::InputFile file;
  try {
    const fricon::qp::LocalProblem p = fricon::io::read_siconos_dat(file.write(data, size));
    const auto n = p.q.size();
    if (p.mu.size() < 1 || n != 3 * p.mu.size() || p.W.rows() != n || p.W.cols() != n) {
      std::fprintf(stderr, "read_siconos_dat returned W %td x %td, q %td, mu %td\n",
                   static_cast<std::ptrdiff_t>(p.W.rows()), static_cast<std::ptrdiff_t>(p.W.cols()),
                   static_cast<std::ptrdiff_t>(n), static_cast<std::ptrdiff_t>(p.mu.size()));
      std::abort();
    }
  } catch (const fricon::InputError&) {
    // The expected way to refuse bad input.
  }
  return 0;
}
