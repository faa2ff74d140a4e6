#pragma once
// io (internal): the stages of reading a problem file, one file each.
//   problem_file.cpp     the entry points: text -> TOML document (syntax errors), overrides,
//                        reading, driver::validate;
//   overrides.cpp        --set KEY=VALUE applied to the document;
//   problem_reader.cpp   the document -> driver::Problem, walking the option tables;
//   problem_writer.cpp   driver::Problem -> JSON and TOML, walking the same tables;
//   toml_access.cpp      positions, messages and typed access shared by the above.

#include <string>

#include <toml++/toml.h>

#include "fricon/driver/problem.hpp"
#include "fricon/io/toml_access.hpp"

namespace fricon::io::detail {

/// Applies one "KEY=VALUE" override to the document; the nodes it puts there are recorded in
/// ctx.origins, so that messages name the override. Throws InputError "--set TEXT: ..." (with
/// ctx.override_origin in place of --set, e.g. "fricon.Problem TEXT: ...").
void apply_override(Context& ctx, toml::table& root, const std::string& text);

/// The document -> p, recording the position of every key read in p.positions. Checks types,
/// shapes, unknown, required and unused keys; the values are left to driver::validate.
void read_document(Context& ctx, const toml::table& root, driver::Problem& p);

}  // namespace fricon::io::detail
