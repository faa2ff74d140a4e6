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

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "fricon/contact/friction_law.hpp"
#include "fricon/driver/problem.hpp"

namespace fricon::io {

/// What a problem can hold that a problem file cannot: objects given by code (the Python module).
struct CodeObjects {
  /// The mesh of [mesh] kind = "arrays" (mesh::mesh_from_arrays); a file cannot name one.
  std::shared_ptr<const mesh::TetMesh> mesh;
  /// F of [contact.friction] law = "function", and its name in reports.
  contact::FrictionFunction friction;
  std::string friction_name = "function";
};

/// How a problem is read besides its text.
struct ReadOptions {
  /// "KEY=VALUE" overrides, as read_problem's.
  std::vector<std::string> overrides;
  /// How messages name where an override came from: "--set" (the command line) or, e.g.,
  /// "fricon.Problem" (attributes set in Python).
  std::string override_origin = "--set";
  CodeObjects code;
};

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

/// As parse_problem, with the objects code gives (mesh kind "arrays", law "function") and the
/// name of the overrides' origin. A relative mesh.file is resolved against source_name's folder.
driver::Problem parse_problem(std::string_view text, const std::string& source_name,
                              const ReadOptions& options);

/// The text of the problem file at `path`. Throws InputError naming it if it cannot be read or
/// is a folder.
std::string read_problem_text(const std::string& path);

/// The effective problem as JSON, with the key names of the file and every default filled in.
/// Keys that the file would reject as unused are left out: `contact` when there is no contact,
/// `material.voigt` for an isotropic material (young/poisson for an anisotropic one), and the
/// parameters of the friction laws other than the chosen one. The result, written as TOML, is a
/// valid problem file that reads back to the same Problem.
nlohmann::json to_json(const driver::Problem& problem);

/// to_json as the text of a problem file (TOML), which parse_problem reads back to the same
/// Problem. Throws InputError for what a file cannot hold: a mesh given by code (kind
/// "arrays") or a friction law given by code (law "function").
std::string to_toml(const driver::Problem& problem);

}  // namespace fricon::io
