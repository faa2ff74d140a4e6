#pragma once
// driver: the record of where each value of a problem was given ("file:line:col", "--set
// KEY=VALUE"), for the start of messages (Problem::where).
//
// A problem is copied once per step of a loading path (at_step), and an override that sets a
// path ("--set dirichlet.0.path=[...]", an assignment in Python) is the origin of every element
// of the path. So the record is shared between copies (copying it copies a pointer; the first
// change to a shared record copies it), and each distinct origin text is held once, however
// many keys it is the origin of: its size is linear in the number of keys plus the length of
// the distinct origins.

#include <cstddef>
#include <initializer_list>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

namespace fricon::driver {

class Positions {
 public:
  Positions() = default;
  /// A record of {key path, origin} pairs (tests, problems built in code).
  Positions(std::initializer_list<std::pair<const std::string, std::string>> entries);

  /// Records `origin` as where `key` (a key path: "material.young", "dirichlet[0].path[3]")
  /// was given, replacing what was recorded for it.
  void set(const std::string& key, const std::string& origin);
  /// As set(key, *origin), for an origin shared by many keys (an override's text, which is the
  /// origin of every element of the value it gives): it is held, not copied, and found again
  /// by its address, so that recording it for N keys costs no N times its length.
  void set(const std::string& key, const std::shared_ptr<const std::string>& origin);
  /// The origin of exactly `key`, or null when none is recorded. The pointer is valid until
  /// this record is changed or destroyed.
  const std::string* find(std::string_view key) const;
  bool contains(std::string_view key) const { return find(key) != nullptr; }
  /// The origin of `key`; throws std::out_of_range when none is recorded.
  const std::string& at(std::string_view key) const;

  std::size_t size() const { return data_ ? data_->origin_of.size() : 0; }
  bool empty() const { return size() == 0; }
  /// The number of characters the record holds: its keys and its distinct origins, once each.
  std::size_t text_size() const;
  /// The record as a map key -> origin (a copy, for tests and reports).
  std::map<std::string, std::string, std::less<>> to_map() const;

  friend bool operator==(const Positions& a, const Positions& b) {
    return a.to_map() == b.to_map();
  }
  friend bool operator!=(const Positions& a, const Positions& b) { return !(a == b); }

 private:
  struct Data {
    std::map<std::string, std::size_t, std::less<>> origin_of;  ///< key -> index in origins
    std::vector<std::shared_ptr<const std::string>> origins;    ///< distinct origins
    /// origin text -> index in origins (views of the strings `origins` holds, which a copy of
    /// the data shares).
    std::unordered_map<std::string_view, std::size_t> by_text;
    std::unordered_map<const std::string*, std::size_t> by_address;  ///< shared origins
  };
  /// The data, unshared (copied first if another record shares it).
  Data& own();
  /// The index of `origin` in the data's origins, added if new.
  static std::size_t index_of(Data& d, const std::shared_ptr<const std::string>& origin);

  std::shared_ptr<Data> data_;
};

}  // namespace fricon::driver
