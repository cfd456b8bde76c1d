// The engine's settings (core/settings.hpp) and the scene's `analysis:` keys: each
// declared setting is the key of its name with the declaration's type, unit, range,
// default and meaning; the loader gives it the declaration's default for the
// analysis type; build_scene hands the engine the value read; the engine refuses a
// value outside the declared range under the key `settings.NAME`; and
// docs/reference/engine.md's table is the declarations'. The reverse: every key of
// `analysis:` is either a declared setting or one of the keys the scene keeps for
// itself or hands to the contact layer (listed below), so that a new key is one or
// the other on purpose.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <limits>
#include <set>

#include "declared_key_checks.hpp"
#include "test_support.hpp"
#include "rheodda/contact/contact_settings_specs.hpp"
#include "rheodda/core/engine.hpp"
#include "rheodda/core/settings.hpp"
#include "rheodda/scene/build.hpp"
#include "rheodda/scene/keys.hpp"
#include "rheodda/scene/loader.hpp"

using namespace rheodda;
using namespace rheodda::test;

namespace {

scene::KeyType key_type(core::SettingType t) {
  switch (t) {
    case core::SettingType::number: return scene::KeyType::number;
    case core::SettingType::integer: return scene::KeyType::integer;
    case core::SettingType::flag: return scene::KeyType::flag;
  }
  return scene::KeyType::text;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(engine_settings)

BOOST_AUTO_TEST_CASE(every_engine_setting_is_the_analysis_key_of_its_name_with_its_declaration) {
  BOOST_TEST_REQUIRE(core::setting_specs().size() >= 20u);
  const scene::Analysis fresh{};
  for (const core::SettingSpec& s : core::setting_specs()) {
    BOOST_TEST_CONTEXT("setting " << s.name()) {
      const scene::KeySpec& k = scene::analysis_key(s.name());
      BOOST_TEST((k.type == key_type(s.type)));
      check_key_is_declaration(k, s.parameter, s.type != core::SettingType::flag);
      if (s.type != core::SettingType::flag) BOOST_TEST(scene::key_range_text(k) == s.range_text());
      // Settings{} holds the default of a dynamic analysis; Analysis{}, of the scene's
      // default type, a static one. A key the scene requires has no default of its own.
      BOOST_TEST(*s.parameter.default_value == s.value(core::Settings{}));
      if (k.required.empty()) {
        BOOST_TEST(k.default_text == s.default_text());
        BOOST_TEST(scene::key_number(k.get(fresh)) == s.default_for(false));
      } else {
        BOOST_TEST(k.default_text == "required");
      }
      BOOST_TEST(s.admits(s.default_for(true)));
      BOOST_TEST(s.admits(s.default_for(false)));
    }
  }
}

BOOST_AUTO_TEST_CASE(every_analysis_key_is_a_declared_setting_or_one_the_scene_keeps) {
  // Declared once in the declaration type of laws::SettingSpec: the engine's settings
  // (core/settings.hpp), the contact layer's (contact/contact_settings_specs.hpp), the
  // scene's acceptances (keys.hpp), the settling stage's numbers (core::settle_specs),
  // and the scene's run controls (duration, outputs, guards). Not declared so: the settling
  // stage's map, the output times (a list), the choices and gravity (a vector).
  const std::set<std::string> others{"type", "settle", "time_integration", "scheme", "solver",
                                     "contact_solver", "integrator", "output_times", "history", "gravity"};
  std::multiset<std::string> declared;
  for (const core::SettingSpec& s : core::setting_specs()) declared.insert(s.name());
  for (const contact::ContactSettingSpec& s : contact::contact_setting_specs()) declared.insert(s.name());
  for (const scene::AcceptanceSpec& s : scene::acceptance_specs()) declared.insert(s.name());
  for (const scene::RunControlSpec& s : scene::run_control_specs()) declared.insert(s.name());
  for (const std::string& key : scene::declared_key_names("analysis")) {
    BOOST_TEST_CONTEXT("analysis." << key) {
      BOOST_TEST((declared.count(key) + others.count(key) == 1u),
                 "each key of analysis: is one declared setting or one the scene keeps (not both)");
    }
  }
  for (const std::string& name : declared)
    BOOST_TEST(scene::analysis_key(name).name == name);
  // analysis.settle: the stage's declared numbers and its `type`.
  std::set<std::string> stage{"type"};
  for (const core::SettleSpec& s : core::settle_specs()) BOOST_TEST(stage.insert(s.name()).second);
  const std::vector<std::string> settle_keys = scene::declared_key_names("analysis.settle");
  BOOST_TEST(std::set<std::string>(settle_keys.begin(), settle_keys.end()) == stage);
}

BOOST_AUTO_TEST_CASE(the_loader_gives_each_setting_its_default_by_analysis_type_and_build_hands_it_over) {
  for (const bool dynamic : {false, true}) {
    BOOST_TEST_CONTEXT((dynamic ? "dynamic" : "static")) {
      const std::string text = dynamic ? with("  dt: 0.01", "  dt: 0.01\n  type: dynamic") : kBaseScene;
      const scene::SceneDescription d = scene::parse_scene(text, "defaults.yaml");
      const scene::BuiltScene built = scene::build_scene(d);
      for (const core::SettingSpec& s : core::setting_specs()) {
        BOOST_TEST_CONTEXT("setting " << s.name()) {
          const scene::KeySpec& k = scene::analysis_key(s.name());
          const double read = scene::key_number(k.get(d.analysis));
          // What the engine gets is what the scene read.
          BOOST_TEST(s.value(built.model.settings) == read);
          if (!k.required.empty()) continue;  // dt: the scene's
          if (!s.default_meaning.empty()) continue;  // a mark the loader replaces (fixed_point_stiffness)
          BOOST_TEST(read == s.default_for(dynamic));
        }
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(a_setting_given_reaches_the_engine_and_out_of_range_is_refused_by_both) {
  // One value inside each declared range, other than the default, through the scene; and
  // the engine's own refusal of a value outside it, under settings.NAME.
  for (const core::SettingSpec& s : core::setting_specs()) {
    if (s.type == core::SettingType::flag) continue;
    BOOST_TEST_CONTEXT("setting " << s.name()) {
      // Below the lower bound, or on it where it is excluded (not on a default mark).
      const double lo = s.parameter.min;
      const bool mark = !s.default_meaning.empty() && lo == *s.parameter.default_value;
      const double bad = s.parameter.min_exclusive && !mark ? lo : lo - 1.0;
      BOOST_TEST(!s.admits(bad));
      core::Model m;
      core::BlockDef b;
      b.vertices = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
      m.blocks = {b};
      s.set(m.settings, bad);
      try {
        core::Engine e(m);
        BOOST_ERROR("the engine took " << s.name() << " = " << s.value(m.settings));
      } catch (const core::ModelError& err) {
        BOOST_TEST(err.key() == "settings." + s.name());
        BOOST_TEST(err.message().find(s.range_text()) != std::string::npos, err.what());
      }
      // The scene refuses it at its key.
      const std::string line = "  " + s.name() + ": " + core::setting_number_text(bad);
      const std::string text =
          s.name() == "dt" ? with("  dt: 0.01", line) : with("  dt: 0.01", "  dt: 0.01\n" + line);
      try {
        (void)scene::parse_scene(text, "range.yaml");
        BOOST_ERROR("the scene took " << line);
      } catch (const scene::SceneError& err) {
        BOOST_TEST(err.key() == "analysis." + s.name(), err.what());
        BOOST_TEST(err.line() == (s.name() == "dt" ? 4 : 5), err.what());
      }
      // Inside, away from the default: the value the scene gives is the engine's.
      const double hi = s.parameter.max;
      const bool integer = s.type == core::SettingType::integer;
      double good = std::numeric_limits<double>::quiet_NaN();
      for (double c : {hi < 1e300 ? (lo + hi) / 2.0 : lo + 2.0, lo + 2.0, lo + 0.25})
        if (const double v = integer ? std::floor(c) : c; s.admits(v) && v != s.default_for(false)) {
          good = v;
          break;
        }
      BOOST_TEST(std::isfinite(good));
      if (std::isfinite(good) && s.name() != "dt" && s.name() != "dynamic_ratio") {
        const std::string given = with("  dt: 0.01", "  dt: 0.01\n  " + s.name() + ": " + core::setting_number_text(good));
        try {
          const scene::BuiltScene built = scene::build_scene(scene::parse_scene(given, "given.yaml"));
          BOOST_TEST(s.value(built.model.settings) == good);
        } catch (const scene::SceneError& err) {
          // Refused for what it ties to another key (dt_max without a step control, ...): the
          // key named is its own.
          BOOST_TEST(err.key() == "analysis." + s.name(), err.what());
        }
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(the_engine_docs_table_is_the_declarations) {
  // docs/reference/engine.md holds, between its settings markers, what `rheodda keys
  // --markdown settings` prints (scripts/scene-format-tables.sh writes it).
  check_doc_table("docs/reference/engine.md", "settings", core::settings_table_markdown());
}

BOOST_AUTO_TEST_SUITE_END()
