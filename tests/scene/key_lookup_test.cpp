// The readers' cross-key checks look keys up by handle (scene/src/key_names.hpp,
// MapReader in yaml_reader.hpp): a handle of another map than the reader's throws
// std::logic_error at the lookup (its word may name another key there, or none); a
// lookup by a name known only at run time (find_named, child_named) of a name that is
// not a key of the map throws the same, instead of finding nothing, which would turn a
// check off without a word; an unknown key in the file stays the user's error (file,
// line, key).
#include <boost/test/unit_test.hpp>

#include <yaml-cpp/yaml.h>

#include <stdexcept>

#include "rheodda/scene/error.hpp"
#include "yaml_reader.hpp"

using namespace rheodda::scene;
namespace key = rheodda::scene::detail::key;

BOOST_AUTO_TEST_SUITE(key_lookup)

BOOST_AUTO_TEST_CASE(a_handle_looks_up_its_key_in_a_map_of_its_map) {
  const detail::Ctx ctx{"lookup.yaml"};
  const detail::MapReader m(ctx, YAML::Load("{until: 1, dt: 2}"), "analysis.settle", "analysis.settle",
                            {"until", "dt", "gravity_ramp"});
  BOOST_TEST(m.find(key::settle::until).as<double>() == 1.0);
  BOOST_TEST(!m.has(key::settle::gravity_ramp));  // declared, not given
  BOOST_TEST(m.child(key::settle::gravity_ramp) == "analysis.settle.gravity_ramp");
  BOOST_TEST(m.required(key::settle::dt, "the step").as<double>() == 2.0);
}

BOOST_AUTO_TEST_CASE(a_handle_of_another_map_fails_loudly) {
  const detail::Ctx ctx{"lookup.yaml"};
  // A stage's analysis has a `type`, as the settling stage has: the same word, another key.
  const detail::MapReader m(ctx, YAML::Load("{type: dynamic}"), "stages[0].analysis", "stages.analysis",
                            {"type", "dynamic_ratio"});
  BOOST_TEST(m.has(key::stage_analysis::type));
  BOOST_CHECK_THROW((void)m.find(key::settle::type), std::logic_error);
  BOOST_CHECK_THROW((void)m.has(key::analysis::dynamic_ratio), std::logic_error);
  BOOST_CHECK_THROW((void)m.child(key::analysis::dynamic_ratio), std::logic_error);
  BOOST_CHECK_THROW((void)m.required(key::settle::type, "the type"), std::logic_error);
  try {
    (void)m.find(key::settle::type);
    BOOST_ERROR("the handle of analysis.settle was taken");
  } catch (const std::logic_error& e) {
    BOOST_TEST(std::string(e.what()) ==
                   "stages[0].analysis: the reader asks for 'type' by a handle of the map 'analysis.settle', not of "
                   "this map ('stages.analysis')",
               e.what());
  }
  // A map of names the file gives has no handles.
  const detail::MapReader names(ctx, YAML::Load("{rock: {}}"), "materials", "", {"rock"});
  BOOST_CHECK_THROW((void)names.find(key::material::damping_ratio), std::logic_error);
}

BOOST_AUTO_TEST_CASE(a_lookup_by_a_name_the_map_does_not_declare_fails_loudly) {
  const detail::Ctx ctx{"lookup.yaml"};
  const detail::MapReader m(ctx, YAML::Load("{dt: 1, duration: 2}"), "analysis", "analysis",
                            {"dt", "duration", "dt_max"});
  BOOST_TEST(m.find_named("dt").IsDefined());
  BOOST_TEST(!m.has_named("dt_max"));  // declared, not given
  BOOST_TEST(m.child_named("dt_max") == "analysis.dt_max");
  BOOST_CHECK_THROW((void)m.find_named("dtmax"), std::logic_error);
  BOOST_CHECK_THROW((void)m.has_named("dt_mx"), std::logic_error);
  BOOST_CHECK_THROW((void)m.child_named("max_dt"), std::logic_error);
  BOOST_CHECK_THROW((void)m.required_named("dtmax", "the longest step"), std::logic_error);
  try {
    (void)m.find_named("dtmax");
    BOOST_ERROR("the reader took dtmax");
  } catch (const std::logic_error& e) {
    BOOST_TEST(std::string(e.what()).find("analysis: the reader asks for 'dtmax'") == 0u, e.what());
  }
}

BOOST_AUTO_TEST_CASE(an_unknown_key_in_the_file_is_the_users_error) {
  const detail::Ctx ctx{"lookup.yaml"};
  try {
    (void)detail::MapReader(ctx, YAML::Load("{dt: 1, dtmax: 2}"), "analysis", "analysis", {"dt", "dt_max"});
    BOOST_ERROR("the reader took dtmax");
  } catch (const SceneError& e) {
    BOOST_TEST(e.file() == "lookup.yaml");
    BOOST_TEST(e.line() == 1);
    BOOST_TEST(e.key() == "analysis.dtmax");
    BOOST_TEST(e.message().find("did you mean 'dt_max'?") != std::string::npos, e.what());
  }
}

BOOST_AUTO_TEST_SUITE_END()
