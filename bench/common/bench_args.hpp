#pragma once
// The command line of the benches that are not Google Benchmark programs (those keep their own
// flags): CLI11, as the fricon program, so that every bench prints its usage on --help, refuses
// a bad argument with a message and exit code 1 (never an uncaught exception), and spells its
// options as it always did:
//
//   int main(int argc, char** argv) {
//     CLI::App app{"What the bench measures.", "name_bench"};
//     int reps = 3;
//     app.add_option("--reps", reps, "Repetitions")->capture_default_str();
//     return fricon::bench::run_main(app, argc, argv, [&] { ...; return 0; });
//   }
#include <exception>
#include <functional>
#include <string>
#include <type_traits>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "fricon/core/enum_names.hpp"

namespace fricon::bench {

/// Parses the command line into the options of `app`, then runs `body`, whose value is the exit
/// code. --help prints the usage and returns 0; a bad argument, or an exception out of `body`,
/// prints "<name>: <message>" on stderr and returns 1.
inline int run_main(CLI::App& app, int argc, char** argv, const std::function<int()>& body) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help
    fmt::print(stderr, "{}: {} (see --help)\n", app.get_name(), e.what());
    return 1;
  }
  try {
    return body();
  } catch (const std::exception& e) {
    fmt::print(stderr, "{}: {}\n", app.get_name(), e.what());
    return 1;
  }
}

/// A CLI11 transform for an option of type E or std::vector<E>: it accepts the spellings of enum
/// E (fricon/core/enum_names.hpp), and only those.
template <typename E>
CLI::Validator enum_spelling() {
  std::string names;
  for (const auto& entry : EnumNames<E>::table)
    names += fmt::format("{}{}", names.empty() ? "" : ",", entry.second);
  return CLI::Validator(
      [](std::string& s) -> std::string {
        const auto value = enum_from_name<E>(s);
        if (!value) return fmt::format("'{}' is not {}", s, enum_choices<E>());
        s = std::to_string(static_cast<std::underlying_type_t<E>>(*value));  // what CLI11 reads
        return "";
      },
      "{" + names + "}");
}

/// Makes `option`, of a std::vector, take one comma-separated list per occurrence
/// ("--n 4,8,16"), so that the arguments after it are not taken for more values.
inline CLI::Option* comma_list(CLI::Option* option) {
  return option->delimiter(',')->allow_extra_args(false);
}

}  // namespace fricon::bench
