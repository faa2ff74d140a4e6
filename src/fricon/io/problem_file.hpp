#pragma once
// io: the TOML problem file (docs/problem-file.md) -> driver::Problem, and back to JSON.
//
// The reader checks what is particular to the file: TOML syntax, types, array lengths, unknown
// keys (with a "did you mean" hint), required keys, keys that the chosen friction law or material
// model does not use, and --set. It records where every key was given (Problem::positions) and
// leaves the values to driver::validate, which it calls last. Every message starts with where the
// value came from and the full key path:
//   paper.toml:7:1: material.young: expected a positive number [Pa], got -1.0
//   --set material.young=-1: material.young: expected a positive number [Pa], got -1.0
// Boundary tags are not checked against the mesh here (the mesh does not exist yet).

#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "fricon/driver/problem.hpp"

namespace fricon::io {

/// Reads the problem file at `path` and validates the Problem (driver::validate). `overrides` are
/// "KEY=VALUE" strings (the command line's --set): KEY is a dotted key path, where an integer
/// component indexes an array of tables ("traction.1.value", 0-based; "traction[1].value" is
/// accepted too); VALUE is a TOML value ("[24,8,8]", "2e11", "\"constant\"") or a bare word taken
/// as a string ("constant"). Overrides are applied to the parsed document before it is read, in
/// order, so an overridden key is checked exactly like a key in the file; its position is "--set
/// KEY=VALUE". Throws InputError.
driver::Problem read_problem(const std::string& path,
                             const std::vector<std::string>& overrides = {});

/// As read_problem, from the text of a problem file; `source_name` names it in messages and is
/// stored in Problem::source.
driver::Problem parse_problem(std::string_view text, const std::string& source_name,
                              const std::vector<std::string>& overrides = {});

/// The effective problem as JSON, with the key names of the file and every default filled in.
/// Keys that the file would reject as unused are left out: `contact` when there is no contact,
/// `material.voigt` for an isotropic material (young/poisson for an anisotropic one), and the
/// parameters of the friction laws other than the chosen one. The result, written as TOML, is a
/// valid problem file that reads back to the same Problem.
nlohmann::json to_json(const driver::Problem& problem);

}  // namespace fricon::io
