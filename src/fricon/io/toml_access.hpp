#pragma once
// io (internal to the problem-file reader): where a value of the TOML document came from, how
// messages name it, and typed access to it. Every message starts with the value's position
// ("file:line:col", or "--set KEY=VALUE" for a value an override put there) and its full key
// path, then "expected PHRASE, got VALUE".

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include <toml++/toml.h>

#include "fricon/core/types.hpp"
#include "fricon/driver/positions.hpp"
#include "fricon/io/problem_file.hpp"

namespace fricon::io::detail {

/// The file name, the nodes that --set put into the document (with where they came from), and
/// where the positions of the keys read are recorded (Problem::positions).
struct Context {
  std::string file;
  /// Node -> "--set KEY=VALUE" (override_origin, then the override's text): one string per
  /// override, shared by all the nodes it put there (a path of N values is N nodes).
  std::unordered_map<const toml::node*, std::shared_ptr<const std::string>> origins;
  driver::Positions* positions = nullptr;
  std::string override_origin = "--set";  ///< how an override's origin is named
  const CodeObjects* code = nullptr;      ///< objects given by code (may be null)

  /// "file:line:col" of a key (or of the node when the key has no position), "--set K=V" for a
  /// node from an override, or just "file" when toml++ knows no position.
  std::string where(const toml::node* node, const toml::key* key) const;
};

/// One value of the document with its key path, e.g. "traction[1].value[2]".
struct Field {
  const toml::node* node = nullptr;
  const toml::key* key = nullptr;  ///< null for array elements and the root
  std::string path;
};

/// Records where `f` was given, under its key path, for driver::validate's messages.
const Field& record(const Context& ctx, const Field& f);

[[noreturn]] void fail(const Context& ctx, const Field& f, std::string_view what);
[[noreturn]] void fail_expected(const Context& ctx, const Field& f, std::string_view expected);

/// The value of a node as the user would recognise it, for "got ..." in messages.
std::string describe(const toml::node& n);

/// Element i of array `a` (the value of `f`), recorded.
Field element(const Context& ctx, const Field& f, const toml::array& a, std::size_t i);

// Typed access. `expected` is the phrase of "expected <expected>, got <value>"; the reader checks
// only the type (and that an integer fits its C++ type), driver::validate the range, and both use
// the same phrase for a key.
Real get_real(const Context& ctx, const Field& f, std::string_view expected);
/// An integer no larger than `max` (the range is validate's: the same phrase serves both).
double get_integer(const Context& ctx, const Field& f, std::string_view expected, double max);
std::string get_string(const Context& ctx, const Field& f, std::string_view expected);
bool get_bool(const Context& ctx, const Field& f);
const toml::array& get_array(const Context& ctx, const Field& f, std::string_view expected);

/// A table of the document with the keys it allows; unknown keys are rejected on construction
/// (with the closest allowed key as a hint). Every key that find() finds is recorded.
class TableReader {
 public:
  TableReader(const Context& ctx, const Field& self, std::string_view expected,
              std::vector<std::string_view> allowed);

  const Field& self() const { return self_; }
  std::optional<Field> find(std::string_view key) const;
  /// The key, or InputError "missing required key 'PATH' (WHY)".
  Field require(std::string_view key, std::string_view why = {}) const;

 private:
  void reject_unknown_keys() const;

  const Context& ctx_;
  Field self_;
  std::vector<std::string_view> allowed_;
  const toml::table* table_ = nullptr;
};

/// `file` as the program opens it: a relative path is taken from the problem file's folder.
std::string beside_problem_file(const Context& ctx, const std::string& file);

std::string_view trim(std::string_view s);

}  // namespace fricon::io::detail
