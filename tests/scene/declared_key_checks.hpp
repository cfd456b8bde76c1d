// What the tests of declared settings and properties (engine_settings_test.cpp,
// contact_settings_test.cpp, joint_set_properties_test.cpp) check of a scene key made
// from a declaration: its unit, meaning and, for a number, its range are the declaration's;
// and a docs table generated from declarations is what the docs hold.
#pragma once

#include <boost/test/unit_test.hpp>

#include <stdexcept>
#include <string>
#include <vector>

#include "test_support.hpp"
#include "rheodda/laws/parameters.hpp"
#include "rheodda/scene/keys.hpp"

namespace rheodda::test {

/// The key `name` in `keys`; std::logic_error if there is none.
inline const scene::KeyInfo& key_of(const std::vector<scene::KeyInfo>& keys, const std::string& name) {
  for (const scene::KeyInfo& k : keys)
    if (k.name == name) return k;
  throw std::logic_error("no key " + name);
}

/// The text of `doc` (a path from the source root) between its lines <!-- NAME:begin -->
/// and <!-- NAME:end --> is `expected` (what scripts/scene-format-tables.sh writes there).
inline void check_doc_table(const std::string& doc, const std::string& name, const std::string& expected) {
  const std::string text = read_text(source_path(doc));
  const std::string begin = "<!-- " + name + ":begin -->\n", end = "<!-- " + name + ":end -->";
  const auto b = text.find(begin), e = text.find(end);
  BOOST_TEST_REQUIRE((b != std::string::npos && e != std::string::npos), "no " << name << " markers in " << doc);
  BOOST_TEST(text.substr(b + begin.size(), e - b - begin.size()) == expected,
             doc << "'s table " << name << " is not the declarations': run scripts/scene-format-tables.sh");
}

/// The key `k` states the unit, the meaning and (`with_range`) the range of the declaration `p`.
inline void check_key_is_declaration(const scene::KeyInfo& k, const laws::ParameterSpec& p, bool with_range = true) {
  BOOST_TEST(k.unit == p.unit);
  BOOST_TEST(k.meaning == p.meaning);
  if (!with_range) return;
  BOOST_TEST(k.range.min == p.min);
  BOOST_TEST(k.range.min_exclusive == p.min_exclusive);
  BOOST_TEST(k.range.max == p.max);
  BOOST_TEST(k.range.max_exclusive == p.max_exclusive);
}

}  // namespace rheodda::test
