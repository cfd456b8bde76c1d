// The readers' cross-key checks look keys up by name (scene/src/yaml_reader.hpp,
// MapReader): a name that is not a key of the map (a typo, a key renamed) throws
// std::logic_error at the lookup instead of finding nothing, which would turn the check
// off without a word; an unknown key in the file stays the user's error (file, line, key).
#include <boost/test/unit_test.hpp>

#include <yaml-cpp/yaml.h>

#include <stdexcept>

#include "rheodda/scene/error.hpp"
#include "yaml_reader.hpp"

using namespace rheodda::scene;

BOOST_AUTO_TEST_SUITE(key_lookup)

BOOST_AUTO_TEST_CASE(a_lookup_by_a_name_the_map_does_not_declare_fails_loudly) {
  const detail::Ctx ctx{"lookup.yaml"};
  const detail::MapReader m(ctx, YAML::Load("{dt: 1, duration: 2}"), "analysis", {"dt", "duration", "dt_max"});
  BOOST_TEST(m.find("dt").IsDefined());
  BOOST_TEST(!m.has("dt_max"));  // declared, not given
  BOOST_TEST(m.child("dt_max") == "analysis.dt_max");
  BOOST_CHECK_THROW((void)m.find("dtmax"), std::logic_error);
  BOOST_CHECK_THROW((void)m.has("dt_mx"), std::logic_error);
  BOOST_CHECK_THROW((void)m.child("max_dt"), std::logic_error);
  try {
    (void)m.find("dtmax");
  } catch (const std::logic_error& e) {
    BOOST_TEST(std::string(e.what()).find("analysis: the reader asks for 'dtmax'") == 0u, e.what());
  }
}

BOOST_AUTO_TEST_CASE(an_unknown_key_in_the_file_is_the_users_error) {
  const detail::Ctx ctx{"lookup.yaml"};
  try {
    (void)detail::MapReader(ctx, YAML::Load("{dt: 1, dtmax: 2}"), "analysis", {"dt", "dt_max"});
    BOOST_ERROR("the reader took dtmax");
  } catch (const SceneError& e) {
    BOOST_TEST(e.file() == "lookup.yaml");
    BOOST_TEST(e.line() == 1);
    BOOST_TEST(e.key() == "analysis.dtmax");
    BOOST_TEST(e.message().find("did you mean 'dt_max'?") != std::string::npos, e.what());
  }
}

BOOST_AUTO_TEST_SUITE_END()
