// fricon keys [SECTION]: every key of the problem file, one markdown table per section, as
// docs/problem-file.md shows them (they are printed from the option tables the reader uses).
#include <memory>
#include <string>

#include <fmt/format.h>

#include "command.hpp"
#include "fricon/core/error.hpp"
#include "fricon/driver/problem_options.hpp"

namespace fricon::app {

namespace {

int print_keys(const std::string& section) {
  bool found = false;
  for (const driver::OptionTable* t : driver::all_option_tables()) {
    if (!section.empty() && t->doc_id() != section) continue;
    found = true;
    if (section.empty()) fmt::print("## {}\n\n", t->doc_id());
    fmt::print("{}", driver::option_markdown(*t));
    if (section.empty()) fmt::print("\n");
  }
  if (!found) {
    std::string ids;
    for (const driver::OptionTable* t : driver::all_option_tables())
      ids += fmt::format(" {}", t->doc_id());
    throw InputError(
        fmt::format("fricon keys: no section '{}'; the sections are:{}", section, ids));
  }
  return kConverged;
}

}  // namespace

Command define_keys(CLI::App& app) {
  auto section = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand(
      "keys",
      "Print every key of the problem file (type, unit, default, valid values), one markdown\n"
      "table per section, as docs/problem-file.md shows them");
  cmd->add_option("section", *section,
                  "Only this section: top, mesh, material, [[material]], [[dirichlet]],\n"
                  "[[traction]], contact, contact.obstacle, contact.friction, solver, output");
  return {cmd, [section] { return print_keys(*section); }};
}

}  // namespace fricon::app
