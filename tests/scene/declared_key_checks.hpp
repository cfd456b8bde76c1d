// What the tests of declared settings and properties (engine_settings_test.cpp,
// contact_settings_test.cpp, joint_set_properties_test.cpp) check of a scene key made
// from a declaration: its unit, meaning and, for a number, its range are the declaration's.
#pragma once

#include <boost/test/unit_test.hpp>

#include "rheodda/laws/parameters.hpp"
#include "rheodda/scene/keys.hpp"

namespace rheodda::test {

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
