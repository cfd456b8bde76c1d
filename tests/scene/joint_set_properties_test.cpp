// A joint set's properties (contact/joint_set_specs.hpp) and the scene's `joint_sets:`
// keys: each declared property is the key of its name with the declaration's unit, range,
// default and meaning (and, where it may change between steps, the stage key too); a value
// read from a scene file reaches the contact layer's JointSet, `check`'s description and
// summary.json's inputs; a value outside the range is refused by the loader (file, line,
// key) and by the contact layer (JointSetError, the key named) in the same words; and
// `rheodda keys joint_sets` prints the declarations. The reverse: every key of
// `joint_sets:` is a declared property or one the scene keeps (law, record).
#include <boost/test/unit_test.hpp>
#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include <map>
#include <set>

#include "declared_key_checks.hpp"
#include "test_support.hpp"
#include "rheodda/contact/contact_system.hpp"
#include "rheodda/contact/joint_set_specs.hpp"
#include "rheodda/scene/build.hpp"
#include "rheodda/scene/describe.hpp"
#include "rheodda/scene/keys.hpp"
#include "rheodda/scene/loader.hpp"

using namespace rheodda;
using namespace rheodda::test;

namespace {

/// One value inside each declared property's range, other than its default, that the
/// properties hold together (residual at most the peak); every declared property must have one.
const std::map<std::string, double> kGiven{
    {"friction_angle", 35.0},     {"cohesion", 2.0e5},          {"tensile_strength", 1.0e5},
    {"residual_friction_angle", 25.0}, {"residual_cohesion", 1.0e4}, {"normal_stiffness", 1.0e10},
    {"shear_stiffness", 4.0e9},   {"restitution", 0.5}};

/// kBaseScene, dynamic (restitution needs velocities), with joint set `bedding` given `keys`.
std::string scene_with(const std::string& keys) {
  return with("  bedding: {friction_angle: 30}", "  bedding: {" + keys + "}",
              with("  dt: 0.01", "  dt: 0.01\n  type: dynamic"));
}

}  // namespace

BOOST_AUTO_TEST_SUITE(joint_set_properties)

BOOST_AUTO_TEST_CASE(every_declared_property_is_the_joint_sets_key_of_its_name_with_its_declaration) {
  BOOST_TEST_REQUIRE(contact::joint_property_specs().size() == 8u);
  const std::vector<scene::KeyInfo> keys = scene::declared_keys("joint_sets");
  const std::vector<scene::KeyInfo> stage = scene::declared_keys("stages.joint_sets");
  std::set<std::string> declared, changeable;
  for (const contact::JointPropertySpec& s : contact::joint_property_specs()) {
    BOOST_TEST_CONTEXT("property " << s.name()) {
      declared.insert(s.name());
      const scene::KeyInfo& k = key_of(keys, s.name());
      BOOST_TEST((k.type == scene::KeyType::number));
      check_key_is_declaration(k, s.parameter);
      // The default is JointProperties{}'s; friction_angle the scene requires.
      BOOST_TEST((s.value(contact::JointProperties{}) == s.parameter.default_value));
      if (s.name() == "friction_angle")
        BOOST_TEST(k.default_text == "required");
      else
        BOOST_TEST(k.default_text == s.default_text());
      if (s.parameter.default_value) BOOST_TEST(s.admits(*s.parameter.default_value));
      else BOOST_TEST(!s.unset_meaning.empty());
      // A property that may change between steps is a stage's key, with the same declaration.
      if (s.between_steps) {
        changeable.insert(s.name());
        const scene::KeyInfo& c = key_of(stage, s.name());
        BOOST_TEST(c.unit == k.unit);
        BOOST_TEST(c.meaning == k.meaning);
        BOOST_TEST(scene::key_range_text(c) == scene::key_range_text(k));
        BOOST_TEST(c.default_text == "unchanged");
      }
    }
  }
  // The reverse: the keys the scene keeps for itself are the only others.
  for (const std::string& key : scene::declared_key_names("joint_sets"))
    BOOST_TEST((declared.count(key) + (key == "law" || key == "record") == 1u), "joint_sets." << key);
  for (const std::string& key : scene::declared_key_names("stages.joint_sets"))
    BOOST_TEST((changeable.count(key) + (key == "law") == 1u), "stages.joint_sets." << key);
}

BOOST_AUTO_TEST_CASE(a_value_read_reaches_the_contact_layer_check_and_summary) {
  std::string keys;
  for (const contact::JointPropertySpec& s : contact::joint_property_specs()) {
    BOOST_TEST_REQUIRE(kGiven.count(s.name()) == 1u, "no test value for the declared property " << s.name());
    const double v = kGiven.at(s.name());
    BOOST_TEST_REQUIRE(s.admits(v));
    BOOST_TEST_REQUIRE((v != s.parameter.default_value));
    keys += (keys.empty() ? "" : ", ") + s.name() + ": " + scene::exact_number(v);
  }
  const scene::SceneDescription d = scene::parse_scene(scene_with(keys), "given.yaml");
  const scene::BuiltScene built = scene::build_scene(d);
  BOOST_TEST_REQUIRE(d.joint_sets[0].name == "bedding");
  BOOST_TEST_REQUIRE(built.joint_sets[0].name == "bedding");
  const nlohmann::json inputs = nlohmann::json::parse(scene::scene_json_text(d));
  const std::string check = scene::describe_scene(d);
  const std::vector<scene::KeyInfo> keys_declared = scene::declared_keys("joint_sets");
  for (const contact::JointPropertySpec& s : contact::joint_property_specs()) {
    BOOST_TEST_CONTEXT("property " << s.name()) {
      const double v = kGiven.at(s.name());
      BOOST_TEST((s.value(d.joint_sets[0]) == v));      // the loader
      BOOST_TEST((s.value(built.joint_sets[0]) == v));  // the contact layer's JointSet
      const scene::KeyInfo& k = key_of(keys_declared, s.name());
      if (k.echoed) BOOST_TEST(inputs.at("joint_sets").at("bedding").at(s.name()).get<double>() == v);
      BOOST_TEST(check.find(s.name() + " " + fmt::format("{:g}", v)) != std::string::npos, check);
    }
  }
  // The contact system takes them.
  contact::ContactSettings settings;
  settings.penalty = 1e10;
  BOOST_CHECK_NO_THROW(contact::ContactSystem(built.joint_sets, settings));
}

BOOST_AUTO_TEST_CASE(out_of_range_is_refused_by_the_loader_and_the_contact_layer_in_the_same_words) {
  for (const contact::JointPropertySpec& s : contact::joint_property_specs()) {
    BOOST_TEST_CONTEXT("property " << s.name()) {
      const double bad = s.parameter.min_exclusive ? s.parameter.min : s.parameter.min - 1.0;
      BOOST_TEST_REQUIRE(!s.admits(bad));
      // The loader: file, line and key.
      const std::string keys = s.name() == "friction_angle"
                                   ? "friction_angle: " + scene::exact_number(bad)
                                   : "friction_angle: 30, " + s.name() + ": " + scene::exact_number(bad);
      std::string loader_message;
      try {
        (void)scene::parse_scene(scene_with(keys), "range.yaml");
        BOOST_ERROR("the scene took " << s.name() << " = " << bad);
      } catch (const scene::SceneError& err) {
        BOOST_TEST(err.key() == "joint_sets.bedding." + s.name(), err.what());
        BOOST_TEST(err.line() == 10, err.what());  // kBaseScene's line 9, after the added `type`
        BOOST_TEST(std::string(err.what()).find("range.yaml:10:") != std::string::npos, err.what());
        loader_message = err.message();
      }
      // The contact layer, given the value directly: the key as data, the loader's message.
      contact::JointSet j;
      j.name = "bedding";
      j.friction_angle = 30.0;
      s.set(j, bad);
      contact::ContactSettings settings;
      settings.penalty = 1e10;
      try {
        contact::ContactSystem cs({j}, settings);
        BOOST_ERROR("the contact layer took " << s.name() << " = " << bad);
      } catch (const contact::JointSetError& err) {
        BOOST_TEST(err.key() == s.name());
        BOOST_TEST(err.joint_set() == 0u);
        BOOST_TEST(err.message() == loader_message);
      }
    }
  }
  // What ties properties together stays a check of its own, named by the residual's key.
  try {
    (void)scene::parse_scene(scene_with("friction_angle: 20, residual_friction_angle: 25"), "residual.yaml");
    BOOST_ERROR("a residual friction angle above the peak was accepted");
  } catch (const scene::SceneError& err) {
    BOOST_TEST(err.key() == "joint_sets.bedding.residual_friction_angle", err.what());
    BOOST_TEST(err.message().find("above the peak friction_angle 20 deg") != std::string::npos, err.what());
  }
}

BOOST_AUTO_TEST_CASE(rheodda_keys_prints_the_declarations) {
  const CommandResult r = run_rheodda("keys joint_sets");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.output);
  const std::vector<scene::KeyInfo> keys = scene::declared_keys("joint_sets");
  for (const contact::JointPropertySpec& s : contact::joint_property_specs()) {
    const scene::KeyInfo& k = key_of(keys, s.name());
    const std::string line = "joint_sets." + s.name() + " [" + s.parameter.unit + "] " + scene::key_range_text(k) +
                             " default " + k.default_text + ": " + s.parameter.meaning + "\n";
    BOOST_TEST(r.output.find(line) != std::string::npos, "no line " << line << " in\n" << r.output);
  }
}

BOOST_AUTO_TEST_SUITE_END()
