// io: the problem file's entry points: the text -> a TOML document (with syntax errors shown at
// their line), the --set overrides, the reading (problem_reader.cpp) and driver::validate.
#include "fricon/io/problem_file.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "fricon/core/error.hpp"
#include "fricon/io/problem_file_stages.hpp"
#include "fricon/io/toml_access.hpp"

namespace fricon::io {

namespace {

using detail::trim;

/// Line `line` (1-based) of `text` without its end of line; empty past the end.
std::string_view line_of(std::string_view text, std::size_t line) {
  std::size_t begin = 0;
  for (std::size_t l = 1; l < line; ++l) {
    begin = text.find('\n', begin);
    if (begin == std::string_view::npos) return {};
    ++begin;
  }
  std::string_view rest = text.substr(std::min(begin, text.size()));
  rest = rest.substr(0, std::min(rest.find('\n'), rest.size()));
  if (!rest.empty() && rest.back() == '\r') rest.remove_suffix(1);
  return rest;
}

/// Whether 1-based `column` is just past the end of `line` (toml++ counts columns in code points
/// or bytes: either is accepted).
bool at_end_of_line(std::string_view line, std::size_t column) {
  const auto code_points =
      static_cast<std::size_t>(std::count_if(line.begin(), line.end(), [](char c) {
        return (static_cast<unsigned char>(c) & 0xC0) != 0x80;
      }));
  return column == code_points + 1 || column == line.size() + 1;
}

/// The line of a syntax error as it is shown in the message: trimmed, shortened, control
/// characters replaced by '?'.
std::string quote_line(std::string_view line) {
  line = trim(line);
  constexpr std::size_t kMax = 60;
  std::string out;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const auto c = static_cast<unsigned char>(line[i]);
    // Cut at a code point boundary.
    if (out.size() >= kMax && (c & 0xC0) != 0x80) return out + "...";
    out += (c < 0x20 || c == 0x7F) ? '?' : static_cast<char>(c);
  }
  return out;
}

}  // namespace

driver::Problem parse_problem(std::string_view text, const std::string& source_name,
                              const std::vector<std::string>& overrides) {
  ReadOptions options;
  options.overrides = overrides;
  return parse_problem(text, source_name, options);
}

driver::Problem parse_problem(std::string_view text, const std::string& source_name,
                              const ReadOptions& options) {
  detail::Context ctx;
  ctx.file = source_name;
  ctx.override_origin = options.override_origin;
  ctx.code = &options.code;
  toml::table root;
  try {
    root = toml::parse(text, std::string_view(source_name));
  } catch (const toml::parse_error& e) {
    const auto& b = e.source().begin;
    const std::string_view line = line_of(text, b.line);
    // toml++ reports a string left open at the end of its line as a control character (the
    // newline) inside the string.
    const bool open_string = e.description().find("control characters") != std::string_view::npos &&
                             at_end_of_line(line, b.column);
    // The offending line names the key; not when the text is not UTF-8 (it cannot be shown).
    const bool show =
        !trim(line).empty() && e.description().find("utf-8") == std::string_view::npos;
    throw InputError(
        fmt::format("{}:{}:{}: invalid TOML: {}{}{}", source_name, b.line, b.column,
                    e.description(), show ? fmt::format(" in `{}`", quote_line(line)) : "",
                    open_string ? " (is the closing quote of a string missing?)" : ""));
  }
  for (const auto& o : options.overrides)
    detail::apply_override(ctx, root, o);
  driver::Problem problem;
  detail::read_document(ctx, root, problem);
  driver::validate(problem);
  return problem;
}

std::string read_problem_text(const std::string& path) {
  // A folder opens as an empty stream on Linux: it would read as a file without keys.
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw InputError(fmt::format(
        "{}: is a folder, not a problem file (give the TOML file, e.g. {}/problem.toml)", path,
        path));
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw InputError(
        fmt::format("{}: cannot open the problem file: {}", path, std::strerror(errno)));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(fmt::format("{}: cannot read the problem file", path));
  return text.str();
}

driver::Problem read_problem(const std::string& path, const std::vector<std::string>& overrides) {
  return parse_problem(read_problem_text(path), path, overrides);
}

}  // namespace fricon::io
