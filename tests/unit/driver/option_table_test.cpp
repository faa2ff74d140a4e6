// driver: the option tables (driver/option_table.hpp, driver/problem_options.cpp) and what is
// derived from them: docs/problem-file.md's key tables, the range phrases, and that the reader,
// the writer and validate() know every key.

#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "fricon/core/error.hpp"
#include "fricon/core/range.hpp"
#include "fricon/driver/problem.hpp"
#include "fricon/driver/problem_options.hpp"

namespace fricon::driver {
namespace {

using ::testing::HasSubstr;

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(OptionTables, DocsShowTheTables) {
  // Every key table of the page is the program's own, character for character.
  const std::string doc = read_text(std::string(FRICON_SOURCE_DIR) + "/docs/problem-file.md");
  ASSERT_FALSE(doc.empty());
  // The blocks "<!-- keys: ID -->\nTABLE<!-- /keys -->" (searched by hand: GCC 12 warns inside
  // std::regex at -O1, which the sanitizer build turns into an error).
  constexpr std::string_view kOpen = "<!-- keys: ", kClose = "<!-- /keys -->";
  std::set<std::string> shown;
  for (auto at = doc.find(kOpen); at != std::string::npos; at = doc.find(kOpen, at + 1)) {
    const auto id_end = doc.find(" -->\n", at);
    const auto close = doc.find(kClose, at);
    ASSERT_NE(id_end, std::string::npos);
    ASSERT_NE(close, std::string::npos);
    const std::string id = doc.substr(at + kOpen.size(), id_end - at - kOpen.size());
    const std::string body = doc.substr(id_end + 5, close - id_end - 5);
    const OptionTable* table = nullptr;
    for (const OptionTable* t : all_option_tables())
      if (t->doc_id() == id) table = t;
    ASSERT_NE(table, nullptr) << "docs/problem-file.md shows an unknown section " << id;
    EXPECT_EQ(body, option_markdown(*table))
        << "the key table of " << id << " in docs/problem-file.md differs from the program's: run "
        << "scripts/update_problem_file_keys.py build/apps/fricon/fricon";
    shown.insert(id);
  }
  // Every section is shown but the entries of [[material]], which repeat [material].
  for (const OptionTable* t : all_option_tables()) {
    if (t->doc_id() != "[[material]]") {
      EXPECT_TRUE(shown.count(t->doc_id())) << t->doc_id();
    }
  }
}

TEST(OptionTables, EveryKeyIsDocumentedOnce) {
  for (const OptionTable* t : all_option_tables()) {
    std::set<std::string_view> keys;
    for (const Option& o : t->options) {
      EXPECT_TRUE(keys.insert(o.key).second) << t->doc_id() << "." << o.key << " twice";
      EXPECT_FALSE(o.doc.empty() && o.type != OptionType::Text)
          << t->doc_id() << "." << o.key << " has no documentation line";
    }
    if (!t->selector.empty()) {
      ASSERT_NE(t->find(t->selector), nullptr) << t->doc_id();
      for (const auto k : t->selected)
        EXPECT_NE(t->find(k), nullptr) << t->doc_id() << ": the selector names unknown key " << k;
    }
  }
}

TEST(OptionTables, TheDefaultsAreValid) {
  // Each table's default section passes its own ranges (validate() of the default Problem).
  EXPECT_NO_THROW(validate(Problem{}));
  for (const OptionTable* t : all_option_tables()) {
    const auto s = t->make();
    for (const Option& o : t->options) {
      if (o.is_nested() || !o.is_number() || t->why_unused(s.get(), o)) continue;
      const OptionValue v = o.get(s.get());
      if (const auto* x = std::get_if<double>(&v)) {
        EXPECT_TRUE(o.range.contains(*x)) << t->doc_id() << "." << o.key;
      }
    }
  }
}

TEST(Range, PhrasesAndBounds) {
  EXPECT_EQ(positive("Pa").phrase(), "a positive number [Pa]");
  EXPECT_EQ(non_negative().phrase(), "a number >= 0");
  EXPECT_EQ(open_interval(-1.0, 0.5).phrase(), "a number in (-1, 0.5)");
  EXPECT_EQ(integer_at_least(1).phrase(), "an integer >= 1");
  EXPECT_EQ(integer_in(1, 20).phrase(), "an integer in [1, 20]");
  EXPECT_EQ(any_number("m").phrase(), "a number [m]");
  EXPECT_TRUE(open_interval(0.0, 1.0).contains(0.5));
  EXPECT_FALSE(open_interval(0.0, 1.0).contains(1.0));
  EXPECT_FALSE(positive().contains(0.0));
  EXPECT_TRUE(non_negative().contains(0.0));
  EXPECT_FALSE(any_number().contains(std::numeric_limits<double>::infinity()));
  EXPECT_FALSE(integer_in(1, 20).contains(21));
  try {
    require("OuterOptions::tol", -1.0, positive());
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "OuterOptions::tol: expected a positive number, got -1.0");
  }
  EXPECT_THROW(require("k", std::nan(""), any_number()), InputError);
}

TEST(OptionTables, TheOuterLoopAndTheFileShareOneRange) {
  // [solver] anderson_depth and outer::OuterOptions::anderson_depth: one range, one message.
  Problem p;
  p.solver.outer.anderson_depth = 21;
  try {
    validate(p);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("solver.anderson_depth: expected an integer in [1, 20]"));
  }
  try {
    p.solver.outer.validate();
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("anderson_depth: expected an integer in [1, 20]"));
  }
}

}  // namespace
}  // namespace fricon::driver
