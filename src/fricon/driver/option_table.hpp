#pragma once
// driver: option tables, the one description of every key of the problem file.
//
// Each section of the problem file ([mesh], [solver], [[dirichlet]], [contact.friction], ...) is
// described by one OptionTable: per key its member of the section's struct, its type and shape,
// its unit and range (core/range.hpp), whether it is required or used only with some choice, and
// its documentation line. Everything that handles keys walks these tables instead of listing the
// keys again:
//   - the TOML reader (io/problem_file.cpp): allowed keys, types, shapes, required keys, keys the
//     chosen kind/model/law does not use, and --set;
//   - to_json / to_toml (io/problem_file.cpp): the effective problem;
//   - validate() (driver/validate.cpp): every range, then the table's own cross-key check;
//   - docs/problem-file.md: its key tables are printed by `fricon keys` and compared with the
//     page by the tests.
// The default of a key is the default of its member: the tables never repeat it.
//
// Adding a key is one line in its table (driver/problem_options.cpp) plus the member it fills and
// the code that uses it.
//
// A table refers to its section only through type-erased accessors (void pointers to the
// section struct), built by OptionTableBuilder<S> from member pointers or accessor lambdas, so
// that the walkers above are plain functions, not templates.

#include <algorithm>
#include <array>
#include <cstddef>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

#include "fricon/core/enum_names.hpp"
#include "fricon/core/range.hpp"
#include "fricon/core/types.hpp"

namespace fricon::driver {

struct Problem;
struct OptionTable;

/// What a key holds.
enum class OptionType {
  Real,          ///< a number (Option::count: one, exactly N, or a list; Option::rows: a matrix)
  Integer,       ///< an integer (same shapes)
  Boolean,       ///< true or false
  Choice,        ///< one of the spellings of an enum (core/enum_names.hpp)
  Text,          ///< a string
  Table,         ///< a nested table ([contact.friction], an inline table)
  TableArray,    ///< an array of tables ([[dirichlet]])
  TableOrArray,  ///< one table for everything, or an array of tables ([material] / [[material]])
};

/// A value as the tables move it between a section, the file and the report: nothing (an
/// optional member that is absent), a boolean, a number (integers too), a string, or numbers
/// (an array, a list or a matrix in row order).
using OptionValue = std::variant<std::monostate, bool, double, std::string, std::vector<double>>;

/// Option::count of a list: any number of values, at least one.
inline constexpr int kList = -1;

/// One key of a section.
struct Option {
  std::string_view key;
  OptionType type = OptionType::Real;
  int count = 0;  ///< numbers: 0 one value, N > 0 exactly N, kList a non-empty list
  int rows = 0;   ///< numbers: > 0 for a matrix of `rows` arrays of `count`
  /// numbers, a list: > 0 when the list may also be written as arrays of this many numbers
  /// (read in row order, flat: [[1, 2, 3], [4, 5, 6]] is [1, 2, 3, 4, 5, 6]).
  int list_rows_of = 0;
  Range range;  ///< numbers: the range of each value (its unit included)
  /// The phrase of "expected ..." for a Text (e.g. "a non-empty boundary tag").
  std::string_view phrase;
  bool may_be_empty = false;              ///< Text: "" is allowed
  bool is_path = false;                   ///< Text: a file, relative to the problem file's folder
  std::vector<std::string_view> choices;  ///< Choice: the spellings, in the enum's table order
  std::string choice_phrase;              ///< Choice: one of "a", "b"
  std::function<long long(const void*)> raw;  ///< Choice: the enum's underlying value
  /// The member is optional: absent unless given (its default is "absent").
  bool optional = false;
  /// The key must be given (where it is used); `required_why` says why, in the message.
  bool required = false;
  std::string_view required_why;
  bool non_empty = false;          ///< a list: at least one value
  std::string_view doc;            ///< the documentation line of docs/problem-file.md
  std::string_view shown_default;  ///< the default as the docs show it, when not the member's
  /// Whether the section's current choices use the key, and if not, the message why not
  /// (e.g. "only used by patches = \"agglomerate\" (patches is \"mesh\")"). Null: always used.
  std::function<std::optional<std::string>(const void* section)> unused;
  std::string_view used_doc;  ///< when it is used, for the docs ("with `backend = \"petsc\"`")

  std::function<OptionValue(const void* section)> get;
  std::function<void(void* section, const OptionValue&)> set;
  /// Text: what is wrong with a value that has the right type (e.g. "components": letters
  /// other than x, y, z), or nothing.
  std::function<bool(const std::string&)> accepts;
  /// Integer: the largest value the member can hold.
  double integer_max = std::numeric_limits<double>::max();

  // Nested tables (Table, TableArray, TableOrArray).
  const OptionTable& (*table)() = nullptr;        ///< the nested section's table
  const OptionTable& (*array_table)() = nullptr;  ///< TableOrArray: the table of an entry
  std::function<const void*(const void*)> child;  ///< Table: the nested section, null if absent
  std::function<void*(void*)> open;               ///< Table: creates it if absent, returns it
  std::function<std::size_t(const void*)> size;   ///< arrays: the number of entries
  std::function<const void*(const void*, std::size_t)> at;  ///< arrays: entry i
  std::function<void*(void*)> append;                       ///< arrays: a new entry
  /// TableOrArray: whether the array form is in use.
  std::function<bool(const void*)> is_array;

  // Chained settings, for the tables' readability.
  Option& require(std::string_view why = {}) {
    required = true;
    required_why = why;
    return *this;
  }
  Option& at_least_one() {
    non_empty = true;
    return *this;
  }
  Option& show_default(std::string_view text) {
    shown_default = text;
    return *this;
  }
  Option& path() {
    is_path = true;
    return *this;
  }
  Option& or_rows_of(int n) {
    list_rows_of = n;
    return *this;
  }
  Option& allow_empty() {
    may_be_empty = true;
    return *this;
  }

  bool is_number() const { return type == OptionType::Real || type == OptionType::Integer; }
  bool is_nested() const {
    return type == OptionType::Table || type == OptionType::TableArray ||
           type == OptionType::TableOrArray;
  }
  /// The phrase of one value: "a positive number [Pa]", "true or false", "one of ...".
  std::string value_phrase() const;
};

/// One section of the problem file.
struct OptionTable {
  std::string name;  ///< its key path: "" (top level), "mesh", "contact.friction", "dirichlet"
  /// How a message names what was expected where the section stands: "a table [solver]".
  std::string expected;
  std::vector<Option> options;
  /// The key whose choice decides which others are used (mesh.kind, contact.friction.law), read
  /// first; empty if none.
  std::string_view selector;
  /// Per spelling of the selector, the keys that choice uses (among `selected`).
  std::vector<std::pair<std::string_view, std::vector<std::string_view>>> selector_choices;
  /// The keys that some choice of the selector uses; the other keys are always used.
  std::vector<std::string_view> selected;
  /// The message for a key that the current choice does not use.
  std::function<std::string(const void* section, std::string_view key)> unused_by_selector;
  /// Checks between keys, after every value of the section passed its own range. `path` is the
  /// section's key path ("material[1]").
  std::function<void(const Problem&, const std::string& path, const void* section)> check;
  /// A section with every default.
  std::function<std::shared_ptr<void>()> make;

  const Option* find(std::string_view key) const;
  /// How docs/problem-file.md and `fricon keys` name the section: "top", "mesh",
  /// "[[dirichlet]]" (an entry of an array of tables), "contact.friction", ...
  std::string doc_id() const;
  /// Every key, in table order (the order of the docs and of "takes:" in messages).
  std::vector<std::string_view> keys() const;
  /// Whether the section's current selector choice uses `key` (true for keys no choice governs);
  /// if not, the message why (unused_by_selector).
  std::optional<std::string> unused_by_choice(const void* section, std::string_view key) const;
  /// The message of a key that the section does not use, from its selector or its own
  /// condition (Option::unused); nothing when it is used.
  std::optional<std::string> why_unused(const void* section, const Option& option) const;
};

/// "path.key", or "key" at the top level.
std::string join_key(std::string_view path, std::string_view key);

/// The markdown table of a section for docs/problem-file.md: | key | type | unit | default |
/// valid values |, one row per key (nested tables are documented by their own section).
std::string option_markdown(const OptionTable& table);

/// The value of a member of type T as an OptionValue, and back (the conversions the builder
/// uses; `to_option_value` of an absent optional is monostate).
namespace option_detail {

template <typename T>
struct is_std_array : std::false_type {};
template <typename T, std::size_t N>
struct is_std_array<std::array<T, N>> : std::true_type {};
template <typename T>
struct is_optional : std::false_type {};
template <typename T>
struct is_optional<std::optional<T>> : std::true_type {};
template <typename T>
struct is_vector : std::false_type {};
template <typename T>
struct is_vector<std::vector<T>> : std::true_type {};

template <typename T>
OptionValue to_value(const T& v) {
  if constexpr (is_optional<T>::value) {
    return v ? to_value(*v) : OptionValue{};
  } else if constexpr (std::is_same_v<T, bool>) {
    return v;
  } else if constexpr (std::is_arithmetic_v<T>) {
    return static_cast<double>(v);
  } else if constexpr (std::is_enum_v<T>) {
    return std::string(enum_name(v));
  } else if constexpr (std::is_same_v<T, std::string>) {
    return v;
  } else if constexpr (std::is_same_v<T, Vec3>) {
    return std::vector<double>{v[0], v[1], v[2]};
  } else if constexpr (is_std_array<T>::value && is_std_array<typename T::value_type>::value) {
    std::vector<double> out;
    for (const auto& row : v)
      for (const auto x : row)
        out.push_back(static_cast<double>(x));
    return out;
  } else {  // std::array or std::vector of numbers
    std::vector<double> out;
    for (const auto x : v)
      out.push_back(static_cast<double>(x));
    return out;
  }
}

template <typename T>
void from_value(const OptionValue& value, T& v) {
  if constexpr (is_optional<T>::value) {
    if (std::holds_alternative<std::monostate>(value)) {
      v.reset();
    } else {
      from_value(value, v.emplace());
    }
  } else if constexpr (std::is_same_v<T, bool>) {
    v = std::get<bool>(value);
  } else if constexpr (std::is_arithmetic_v<T>) {
    v = static_cast<T>(std::get<double>(value));
  } else if constexpr (std::is_enum_v<T>) {
    v = *enum_from_name<T>(std::get<std::string>(value));
  } else if constexpr (std::is_same_v<T, std::string>) {
    v = std::get<std::string>(value);
  } else {
    const auto& x = std::get<std::vector<double>>(value);
    if constexpr (std::is_same_v<T, Vec3>) {
      v = Vec3(x.at(0), x.at(1), x.at(2));
    } else if constexpr (is_vector<T>::value) {
      v.assign(x.begin(), x.end());
    } else if constexpr (is_std_array<typename T::value_type>::value) {
      const std::size_t n = std::tuple_size_v<typename T::value_type>;
      for (std::size_t i = 0; i < v.size(); ++i)
        for (std::size_t j = 0; j < n; ++j)
          v[i][j] = x.at(i * n + j);
    } else {
      for (std::size_t i = 0; i < v.size(); ++i)
        v[i] = static_cast<typename T::value_type>(x.at(i));
    }
  }
}

/// The plain type behind optional<T>.
template <typename T>
struct plain {
  using type = T;
};
template <typename T>
struct plain<std::optional<T>> {
  using type = T;
};

}  // namespace option_detail

/// Builds the table of section S. Each method adds one key and returns it for chained settings;
/// `field` is a member pointer of S or a callable S& -> member&.
template <typename S>
class OptionTableBuilder {
 public:
  OptionTableBuilder(std::string name, std::string expected) {
    table_.name = std::move(name);
    table_.expected = std::move(expected);
    table_.make = [] { return std::static_pointer_cast<void>(std::make_shared<S>()); };
  }

  /// A number, or an array / list / matrix of numbers (the shape follows the member's type:
  /// Real, int, Index, Vec3, std::array, std::vector, optional of these).
  template <typename F>
  Option& number(std::string_view key, F field, Range range, std::string_view doc) {
    using M = member_t<F>;
    using P = typename option_detail::plain<M>::type;
    Option& o = add(key, field, doc);
    o.range = range;
    o.optional = option_detail::is_optional<M>::value;
    if constexpr (std::is_arithmetic_v<P>) {
      set_number_type<P>(o);
    } else if constexpr (std::is_same_v<P, Vec3>) {
      o.type = OptionType::Real;
      o.count = 3;
    } else if constexpr (option_detail::is_vector<P>::value) {
      set_number_type<typename P::value_type>(o);
      o.count = kList;
    } else if constexpr (option_detail::is_std_array<typename P::value_type>::value) {
      set_number_type<typename P::value_type::value_type>(o);
      o.rows = static_cast<int>(std::tuple_size_v<P>);
      o.count = static_cast<int>(std::tuple_size_v<typename P::value_type>);
    } else {
      set_number_type<typename P::value_type>(o);
      o.count = static_cast<int>(std::tuple_size_v<P>);
    }
    o.range.integer = o.type == OptionType::Integer;
    return o;
  }

  template <typename F>
  Option& boolean(std::string_view key, F field, std::string_view doc) {
    Option& o = add(key, field, doc);
    o.type = OptionType::Boolean;
    return o;
  }

  /// One of the spellings of the member's enum.
  template <typename F>
  Option& choice(std::string_view key, F field, std::string_view doc) {
    using E = typename option_detail::plain<member_t<F>>::type;
    Option& o = add(key, field, doc);
    o.type = OptionType::Choice;
    o.optional = option_detail::is_optional<member_t<F>>::value;
    for (const auto& entry : EnumNames<E>::table)
      o.choices.push_back(entry.second);
    o.choice_phrase = enum_choices<E>();
    if constexpr (!option_detail::is_optional<member_t<F>>::value)
      o.raw = [field](const void* s) {
        return static_cast<long long>(
            std::invoke(field, const_cast<S&>(*static_cast<const S*>(s))));
      };
    return o;
  }

  /// A string; `phrase` says what is expected ("a non-empty boundary tag").
  template <typename F>
  Option& text(std::string_view key, F field, std::string_view phrase, std::string_view doc) {
    Option& o = add(key, field, doc);
    o.type = OptionType::Text;
    o.phrase = phrase;
    return o;
  }

  /// A string read and written through a conversion: `to` gives the member's text, `from` sets
  /// the member from a text that `accepts` (components = "xyz").
  template <typename F, typename To, typename From, typename Accepts>
  Option& text_as(std::string_view key, F field, std::string_view phrase, std::string_view doc,
                  To to, From from, Accepts accepts) {
    Option& o = text(key, field, phrase, doc);
    o.get = [field, to](const void* s) {
      return OptionValue{to(std::invoke(field, const_cast<S&>(*static_cast<const S*>(s))))};
    };
    o.set = [field, from](void* s, const OptionValue& v) {
      from(std::get<std::string>(v), std::invoke(field, *static_cast<S*>(s)));
    };
    o.accepts = accepts;
    return o;
  }

  /// A nested table, described by `table`; the member is T or optional<T>.
  template <typename F>
  Option& table(std::string_view key, F field, const OptionTable& (*nested_table)(),
                std::string_view doc) {
    using M = member_t<F>;
    Option& o = nested(key, doc, OptionType::Table, nested_table);
    o.optional = option_detail::is_optional<M>::value;
    o.child = [field](const void* s) -> const void* {
      const M& m = std::invoke(field, const_cast<S&>(*static_cast<const S*>(s)));
      if constexpr (option_detail::is_optional<M>::value) {
        return m ? &*m : nullptr;
      } else {
        return &m;
      }
    };
    o.open = [field](void* s) -> void* {
      M& m = std::invoke(field, *static_cast<S*>(s));
      if constexpr (option_detail::is_optional<M>::value) {
        if (!m) m.emplace();
        return &*m;
      } else {
        return &m;
      }
    };
    return o;
  }

  /// An array of tables, each described by `table`; the member is a std::vector.
  template <typename F>
  Option& tables(std::string_view key, F field, const OptionTable& (*nested_table)(),
                 std::string_view doc) {
    Option& o = nested(key, doc, OptionType::TableArray, nested_table);
    set_array_access(o, field);
    return o;
  }

  /// One table (`single`, described by `table`) or an array of tables (`many`, each described
  /// by `array_table`): [material] or [[material]].
  template <typename F, typename G>
  Option& table_or_tables(std::string_view key, F single, const OptionTable& (*single_table)(),
                          G many, const OptionTable& (*array_table)(), std::string_view doc) {
    Option& o = nested(key, doc, OptionType::TableOrArray, single_table);
    o.array_table = array_table;
    o.child = [single](const void* s) -> const void* {
      return &std::invoke(single, const_cast<S&>(*static_cast<const S*>(s)));
    };
    o.open = [single](void* s) -> void* { return &std::invoke(single, *static_cast<S*>(s)); };
    o.is_array = [many](const void* s) {
      return !std::invoke(many, const_cast<S&>(*static_cast<const S*>(s))).empty();
    };
    set_array_access(o, many);
    return o;
  }

  /// One table or an array of tables, both read into one vector `many` (each entry described
  /// by `table`): [contact] is one entry, [[contact]] one per table; written back as a table
  /// when there is one entry. Absent: empty.
  template <typename F>
  Option& table_or_tables(std::string_view key, F many, const OptionTable& (*entry_table)(),
                          std::string_view doc) {
    Option& o = nested(key, doc, OptionType::TableOrArray, entry_table);
    o.array_table = entry_table;
    o.optional = true;
    o.child = [many](const void* s) -> const void* {
      const auto& v = std::invoke(many, const_cast<S&>(*static_cast<const S*>(s)));
      return v.size() == 1 ? &v.front() : nullptr;
    };
    o.open = [many](void* s) -> void* {
      return &std::invoke(many, *static_cast<S*>(s)).emplace_back();
    };
    o.is_array = [many](const void* s) {
      return std::invoke(many, const_cast<S&>(*static_cast<const S*>(s))).size() > 1;
    };
    set_array_access(o, many);
    return o;
  }

  /// The last key added is used only when `used(section)`; else `why(section)` is the message;
  /// `doc` says when it is used, for the docs.
  template <typename Used, typename Why>
  void when(Used used, Why why, std::string_view doc) {
    Option& o = table_.options.back();
    o.unused = [used, why](const void* s) -> std::optional<std::string> {
      const S& section = *static_cast<const S*>(s);
      if (used(section)) return std::nullopt;
      return std::string(why(section));
    };
    o.used_doc = doc;
  }

  /// The choice key `key` (a member enum E, added with choice()) selects which of the other keys
  /// are used: `keys_of(value)` lists those of a choice (e.g. contact::friction_law_parameters);
  /// `message(section, key)` says why a key is unused.
  template <typename F, typename KeysOf, typename Message>
  void selector(std::string_view key, F /*field: its type names the enum*/, KeysOf keys_of,
                Message message) {
    using E = member_t<F>;
    table_.selector = key;
    for (const auto& [value, name] : EnumNames<E>::table) {
      const auto keys = keys_of(value);
      table_.selector_choices.emplace_back(name,
                                           std::vector<std::string_view>(keys.begin(), keys.end()));
      for (const auto k : keys)
        if (std::find(table_.selected.begin(), table_.selected.end(), k) == table_.selected.end())
          table_.selected.push_back(k);
    }
    table_.unused_by_selector = [message](const void* s, std::string_view k) {
      return std::string(message(*static_cast<const S*>(s), k));
    };
  }

  /// Checks between the section's keys (validate(), after the ranges).
  template <typename Check>
  void check(Check c) {
    table_.check = [c](const Problem& p, const std::string& path, const void* s) {
      c(p, path, *static_cast<const S*>(s));
    };
  }

  OptionTable build() { return std::move(table_); }

 private:
  template <typename F>
  using member_t = std::remove_cvref_t<std::invoke_result_t<F, S&>>;

  template <typename T>
  static void set_number_type(Option& o) {
    if constexpr (std::is_floating_point_v<T>) {
      o.type = OptionType::Real;
    } else {
      o.type = OptionType::Integer;
      o.integer_max = static_cast<double>(std::numeric_limits<T>::max());
    }
  }

  template <typename F>
  Option& add(std::string_view key, F field, std::string_view doc) {
    Option& o = table_.options.emplace_back();
    o.key = key;
    o.doc = doc;
    o.get = [field](const void* s) {
      return option_detail::to_value(std::invoke(field, const_cast<S&>(*static_cast<const S*>(s))));
    };
    o.set = [field](void* s, const OptionValue& v) {
      option_detail::from_value(v, std::invoke(field, *static_cast<S*>(s)));
    };
    return o;
  }

  Option& nested(std::string_view key, std::string_view doc, OptionType type,
                 const OptionTable& (*nested_table)()) {
    Option& o = table_.options.emplace_back();
    o.key = key;
    o.doc = doc;
    o.type = type;
    o.table = nested_table;
    return o;
  }

  template <typename F>
  static void set_array_access(Option& o, F field) {
    o.size = [field](const void* s) {
      return std::invoke(field, const_cast<S&>(*static_cast<const S*>(s))).size();
    };
    o.at = [field](const void* s, std::size_t i) -> const void* {
      return &std::invoke(field, const_cast<S&>(*static_cast<const S*>(s)))[i];
    };
    o.append = [field](void* s) -> void* {
      return &std::invoke(field, *static_cast<S*>(s)).emplace_back();
    };
  }

  OptionTable table_;
};

/// A field two members deep: at(&SolverOptions::outer, &outer::OuterOptions::tol).
template <typename S, typename M, typename T>
auto at(M S::*outer, T M::*inner) {
  return [outer, inner](S& s) -> T& { return (s.*outer).*inner; };
}

}  // namespace fricon::driver
