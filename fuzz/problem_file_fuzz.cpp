// libFuzzer target for the problem-file reader (src/fricon/io/problem_file.cpp).
//
// The input is the text of a problem file, optionally followed by command-line overrides: the
// bytes up to the first NUL are the file, each NUL-separated piece after it is one `--set`
// argument (KEY=VALUE). Whatever the bytes, parse_problem must either return a Problem or throw
// fricon::InputError; any other exception (it escapes and aborts), a crash, a hang or a sanitizer
// report is a finding. A Problem that is returned is also converted back to JSON (to_json).
//
// Build and run: fuzz/run.sh [SECONDS] (or `make fuzz`); see docs/fuzzing.md.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "fricon/core/error.hpp"
#include "fricon/io/problem_file.hpp"

namespace {

// A known bug of toml++ 3.3.0 (Debian's version), not of fricon:
// is_non_ascii_horizontal_whitespace() reaches TOML_UNREACHABLE for some code points in
// U+00A1..U+FEFE (marzer/tomlplusplus issue #295, fixed upstream by pull request #305). UBSan stops
// on it at once, so inputs that contain such a code point are skipped to let the run look for other
// findings. The test below mirrors the generated function: the code points it does not classify are
// exactly the affected ones.
bool hits_known_toml_bug(char32_t c) {
  if (c < 0xA0 || c > 0xFEFF || c == 0xA0 || c == 0x3000 || c == 0xFEFF) return false;
  const auto child = (static_cast<std::uint64_t>(c) - 0xA0) / 0x3FA;
  if (((std::uint64_t{1} << child) & 0x7FFFFFFFFFFFF75Eull) != 0) return false;
  return child != 0x05 && child != 0x07;
}

/// Whether the bytes, read as UTF-8 (invalid sequences skipped), hold an affected code point.
bool has_known_toml_bug(std::string_view s) {
  for (std::size_t i = 0; i < s.size(); ++i) {
    const auto b = static_cast<unsigned char>(s[i]);
    const std::size_t n = b >= 0xF0 ? 3 : b >= 0xE0 ? 2 : b >= 0xC0 ? 1 : 0;
    if (n == 0 || n == 3 || i + n >= s.size()) continue;  // ASCII, 4 bytes (> U+FFFF), or cut
    char32_t c = b & (n == 1 ? 0x1F : 0x0F);
    bool ok = true;
    for (std::size_t k = 1; k <= n; ++k) {
      const auto cont = static_cast<unsigned char>(s[i + k]);
      ok = ok && (cont & 0xC0) == 0x80;
      c = (c << 6) | (cont & 0x3F);
    }
    if (ok && hits_known_toml_bug(c)) return true;
  }
  return false;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const std::size_t nul = input.find('\0');
  const std::string_view text = input.substr(0, nul);
  std::vector<std::string> overrides;
  if (nul != std::string_view::npos) {
    std::string_view rest = input.substr(nul + 1);
    while (true) {
      const std::size_t next = rest.find('\0');
      overrides.emplace_back(rest.substr(0, next));
      if (next == std::string_view::npos) break;
      rest = rest.substr(next + 1);
    }
  }
  if (has_known_toml_bug(input)) return -1;  // -1: not added to the corpus
  try {
    const fricon::driver::Problem problem = fricon::io::parse_problem(text, "fuzz.toml", overrides);
    (void)fricon::io::to_json(problem).dump();
  } catch (const fricon::InputError&) {
    // The expected way to refuse bad input.
  }
  return 0;
}
