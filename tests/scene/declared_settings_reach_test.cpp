// A setting declared in one place reaches every reader of `analysis:` (issue 53): for
// each declaration of the engine's settings (core/settings.hpp: setting_specs and the
// settling stage's settle_specs), the contact layer's (contact/contact_settings_specs.hpp)
// and the scene's acceptances (keys.hpp), a value given in a scene file is what the loader
// read, what the engine gets (build_scene's Model or ContactSettings), what `check` shows,
// what summary.json's inputs echo, and its key's row of the docs table is the declaration's.
// tests/python/test_declared_settings.py follows the same declarations into Python.
//
// The choices (laws::ChoiceSpec: core's choice_specs and settle_choice_specs, the contact
// layer's contact_choice_specs) the same way: each of a choice's words given in a file
// reaches the loader, the engine's struct, summary.json, and its docs row is the
// declaration's; a word not among them is refused naming the file, line, key and the words.
//
// A value is taken inside the declared range, away from the default; a setting that only
// applies with another key gets that key from kContext, so that a new declaration either
// passes as it is or fails here until its context is stated.
#include <boost/test/unit_test.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>

#include "declared_key_checks.hpp"
#include "test_support.hpp"
#include "rheodda/contact/contact_settings_specs.hpp"
#include "rheodda/core/engine.hpp"
#include "rheodda/core/property_specs.hpp"
#include "rheodda/core/settings.hpp"
#include "rheodda/scene/build.hpp"
#include "rheodda/scene/describe.hpp"
#include "rheodda/scene/keys.hpp"
#include "rheodda/scene/loader.hpp"

using namespace rheodda;
using namespace rheodda::test;

namespace {

/// Lines a setting needs beside it in `analysis:` (two spaces in) to apply.
const std::map<std::string, std::string> kContext{
    {"dynamic_ratio", "  type: dynamic\n"},
    {"step_extrapolation", "  step_tolerance: 0.001\n"},
    {"dt_max", "  creep_tolerance: 0.001\n"},
    {"explicit_safety", "  integrator: automatic\n"},
    {"explicit_damping", "  integrator: automatic\n"},
    {"stage_local_damping", "  integrator: automatic\n"},
    {"stage_cycles", "  integrator: automatic\n"},
    {"static_force_ratio", "  integrator: explicit\n"},
    {"static_max_cycles", "  integrator: explicit\n  static_force_ratio: 1e-5\n"},
    {"static_local_damping", "  integrator: explicit\n  static_force_ratio: 1e-5\n"},
    {"settle.force_ratio", "  integrator: explicit\n"},
};

/// Values the generic choice (mid-range, or the lower bound + 2) would make refused for
/// what they tie to: the scene's duration is 1, its dt 0.01, its stage ends at 0.5.
const std::map<std::string, double> kValue{
    {"dt", 0.005},          {"settle.until", 0.25},        {"settle.dt", 0.005},
    {"settle.collapse_dt", 0.002}, {"settle.gravity_ramp", 0.25}, {"settle.force_ratio", 1e-5},
    {"duration", 2.0},      {"output_interval", 0.5},
};

/// The keys whose default the scene states itself: required ones, and the penalty's rule.
const std::set<std::string> kSceneDefault{"dt", "duration", "penalty", "settle.until", "settle.dt"};

/// A value of the declaration `s` inside its range, other than its default(s).
template <class S>
double given_value(const laws::SettingSpec<S>& s, const std::string& key) {
  if (const auto v = kValue.find(key); v != kValue.end()) return v->second;
  if (s.type == laws::SettingType::flag) return *s.parameter.default_value == 0.0 ? 1.0 : 0.0;
  const double lo = s.parameter.min, hi = s.parameter.max;
  for (double c : {hi < 1e300 ? (lo + hi) / 2.0 : lo + 2.0, lo + 2.0, lo + 0.25}) {
    const double v = s.type == laws::SettingType::integer ? std::floor(c) : c;
    if (s.admits(v) && v != s.default_for(false) && v != s.default_for(true)) return v;
  }
  BOOST_FAIL("no value for " << key);
  return 0.0;
}

/// The value as the scene file and `check` write it.
std::string value_text(double v, laws::SettingType type) {
  if (type == laws::SettingType::flag) return v != 0.0 ? "true" : "false";
  if (type == laws::SettingType::integer) return fmt::format("{:.0f}", v);
  return fmt::format("{:g}", v);
}

/// The scene of kBaseScene with `line` under `analysis:` (a setting of the map `analysis`)
/// or in a dynamic settling stage (`analysis.settle`), with the setting's context.
std::string scene_with(const std::string& map, const std::string& key, const std::string& line) {
  const std::string context = kContext.count(key) ? kContext.at(key) : "";
  if (key == "dt") return with("  dt: 0.01\n", line + "\n");
  if (key == "duration") return with("  duration: 1\n", line + "\n");
  if (map == "analysis") return with("  dt: 0.01\n", "  dt: 0.01\n" + context + line + "\n");
  std::string stage = "  settle: {type: dynamic, until: 0.5, dt: 0.001, " + line + "}\n";
  if (key == "settle.force_ratio") stage = "  settle: {type: dynamic, until: 0.5, dt: 0.001, rest_tolerance: 0.01, " + line + "}\n";
  if (key == "settle.until") stage = "  settle: {type: dynamic, dt: 0.001, " + line + "}\n";
  if (key == "settle.dt") stage = "  settle: {type: dynamic, until: 0.5, " + line + "}\n";
  return with("  dt: 0.01\n", "  dt: 0.01\n" + context + stage);
}

/// Each declaration of `specs` in `map`: the key of its name, with the declaration's row in
/// the docs table; a value given reaches the loader, `engine` (the part of what build_scene
/// makes that the declaration binds), check and summary.json.
template <class S, class Engine>
void reaches(const std::vector<laws::SettingSpec<S>>& specs, const std::string& map, Engine engine) {
  const std::string table = scene::key_table_markdown(map);
  const std::vector<scene::KeyInfo> keys = scene::declared_keys(map);
  for (const laws::SettingSpec<S>& s : specs) {
    const std::string key = map == "analysis" ? s.name() : "settle." + s.name();
    BOOST_TEST_CONTEXT("analysis." << key) {
      // The docs: its row is the declaration's unit, range and meaning (the default is the
      // declaration's, or what the scene says of a key it requires).
      const scene::KeyInfo& k = key_of(keys, s.name());
      check_key_is_declaration(k, s.parameter, s.type != laws::SettingType::flag);
      const std::string row = fmt::format("| `{}` | {} | {} | {} | ", s.name(), s.parameter.unit,
                                          s.type == laws::SettingType::flag ? "" : s.range_text(), s.parameter.meaning);
      BOOST_TEST(table.find(row) != std::string::npos, row);
      if (kSceneDefault.count(key) == 0u) BOOST_TEST(table.find(row + s.default_text() + " |\n") != std::string::npos);
      // A value given in a file.
      const double v = given_value(s, key);
      const std::string text = value_text(v, s.type);
      const scene::SceneDescription d = scene::parse_scene(scene_with(map, key, "  " + s.name() + ": " + text), "given.yaml");
      const scene::Analysis& a = d.analysis;
      if constexpr (std::is_same_v<S, core::SettleStage>) {
        BOOST_TEST(s.value(a.settle) == v);  // the loader
      } else {
        BOOST_TEST(s.value(a) == v);
      }
      const scene::BuiltScene built = scene::build_scene(d);
      engine(s, built, v);
      const std::string check = scene::describe_scene(d);
      BOOST_TEST(check.find(" " + key + " " + text) != std::string::npos, check);
      const nlohmann::json inputs = nlohmann::json::parse(scene::scene_json_text(d)).at("analysis");
      const nlohmann::json& echoed = map == "analysis" ? inputs : inputs.at("settle");
      if (s.type == laws::SettingType::flag)  // summary.json echoes every key of `analysis` (scene_json.cpp)
        BOOST_TEST(echoed.at(s.name()).template get<bool>() == (v != 0.0));
      else
        BOOST_TEST(echoed.at(s.name()).template get<double>() == v);
    }
  }
}

/// Lines a choice's word needs beside it in `analysis:` (two spaces in) to apply.
const std::map<std::string, std::string> kChoiceContext{
    {"time_integration: trapezoidal", "  type: dynamic\n"},
    {"integrator: explicit", "  type: dynamic\n"},
    {"integrator: automatic", "  type: dynamic\n"},
};

/// The scene of kBaseScene with the choice `key` (of `map`) given as `word`, and the line it
/// is on.
std::pair<std::string, int> scene_with_choice(const std::string& map, const std::string& key, const std::string& word) {
  if (map == "analysis") {
    const std::string line = "  " + key + ": " + word + "\n";
    const std::string context = kChoiceContext.count(key + ": " + word) ? kChoiceContext.at(key + ": " + word) : "";
    return {with("  dt: 0.01\n", "  dt: 0.01\n" + context + line), 5 + static_cast<int>(std::count(context.begin(), context.end(), '\n'))};
  }
  return {with("  dt: 0.01\n", "  dt: 0.01\n  settle: {type: " + word + ", until: 0.5, dt: 0.001}\n"), 5};
}

/// Each declared choice of `specs` in `map`: its docs row is the declaration's (words,
/// meaning, default the word of the struct's default); each of its words given in a file
/// reaches the loader, `engine` (the word of the engine's struct that build_scene makes)
/// and summary.json; a word not among them is refused naming the file, line, key and words.
template <class S, class Engine>
void choice_reaches(const std::vector<laws::ChoiceSpec<S>>& specs, const std::string& map, Engine engine) {
  const std::string table = scene::key_table_markdown(map);
  const std::vector<scene::KeyInfo> keys = scene::declared_keys(map);
  for (const laws::ChoiceSpec<S>& c : specs) {
    BOOST_TEST_CONTEXT(map << "." << c.name()) {
      const scene::KeyInfo& k = key_of(keys, c.name());
      BOOST_TEST((k.type == scene::KeyType::choice));
      BOOST_TEST(k.choices == c.words, boost::test_tools::per_element());
      BOOST_TEST(k.meaning == c.meaning);
      const std::string row = fmt::format("| `{}` | – |  | {} | ", c.name(), c.meaning);
      BOOST_TEST(table.find(row) != std::string::npos, row);
      BOOST_TEST(table.find(row + c.default_text() + " |\n") != std::string::npos);
      BOOST_TEST(c.default_word() == c.word_of(S{}));
      for (const std::string& word : c.words) {
        BOOST_TEST_CONTEXT("word " << word) {
          const scene::SceneDescription d = scene::parse_scene(scene_with_choice(map, c.name(), word).first, "given.yaml");
          if constexpr (std::is_same_v<S, core::SettleStage>) {
            BOOST_TEST(c.word_of(d.analysis.settle) == word);  // the loader
          } else {
            BOOST_TEST(c.word_of(d.analysis) == word);
          }
          engine(c, scene::build_scene(d), word);
          const nlohmann::json inputs = nlohmann::json::parse(scene::scene_json_text(d)).at("analysis");
          const nlohmann::json& echoed = map == "analysis" ? inputs : inputs.at("settle");
          BOOST_TEST(echoed.at(c.name()).template get<std::string>() == word);
        }
      }
      // A word not among them.
      const auto [text, line] = scene_with_choice(map, c.name(), "nonesuch");
      try {
        (void)scene::parse_scene(text, "bad.yaml");
        BOOST_ERROR("an unknown word was taken");
      } catch (const scene::SceneError& e) {
        BOOST_TEST(std::string(e.what()).find("bad.yaml:" + std::to_string(line) + ":") == 0u, e.what());
        BOOST_TEST(e.key().find(c.name()) != std::string::npos, e.what());
        std::string words;
        for (const std::string& w : c.words) words += (words.empty() ? "" : ", ") + w;
        BOOST_TEST(e.message().find("'nonesuch' is not one of: " + words) != std::string::npos, e.what());
      }
    }
  }
}

}  // namespace

BOOST_AUTO_TEST_SUITE(declared_settings_reach)

BOOST_AUTO_TEST_CASE(an_engine_setting_reaches_the_loader_the_engine_check_summary_and_docs) {
  reaches(core::setting_specs(), "analysis", [](const core::SettingSpec& s, const scene::BuiltScene& b, double v) {
    BOOST_TEST(s.value(b.model.settings) == v);
  });
}

BOOST_AUTO_TEST_CASE(a_settling_stage_setting_reaches_the_loader_the_engine_check_summary_and_docs) {
  reaches(core::settle_specs(), "analysis.settle", [](const core::SettleSpec& s, const scene::BuiltScene& b, double v) {
    BOOST_TEST(s.value(b.model.settings.settle) == v);
  });
}

BOOST_AUTO_TEST_CASE(a_contact_setting_reaches_the_loader_the_contact_layer_check_summary_and_docs) {
  reaches(contact::contact_setting_specs(), "analysis",
          [](const contact::ContactSettingSpec& s, const scene::BuiltScene& b, double v) {
            BOOST_TEST(s.value(b.contact_settings) == v);
          });
}

BOOST_AUTO_TEST_CASE(an_acceptance_reaches_the_loader_check_summary_and_docs) {
  // Not the engine's: the scene's warnings read it (scene_warnings).
  reaches(scene::acceptance_specs(), "analysis", [](const scene::AcceptanceSpec& s, const scene::BuiltScene&, double v) {
    BOOST_TEST(v == 1.0, s.name() << ": an acceptance given is true");
  });
}

BOOST_AUTO_TEST_CASE(a_run_control_reaches_the_loader_check_summary_and_docs) {
  // Not the engine's: the run reads them from the scene (run.cpp).
  reaches(scene::run_control_specs(), "analysis", [](const scene::RunControlSpec& s, const scene::BuiltScene&, double v) {
    BOOST_TEST(s.admits(v), s.name());
  });
}

BOOST_AUTO_TEST_CASE(an_engine_choice_reaches_the_loader_the_engine_summary_and_docs) {
  choice_reaches(core::choice_specs(), "analysis", [](const core::ChoiceSpec& c, const scene::BuiltScene& b, const std::string& w) {
    if (c.name() == "integrator" && w == "automatic")  // chosen before the engine runs (integrator_choice.hpp)
      BOOST_TEST(c.word_of(b.model.settings) != "automatic");
    else
      BOOST_TEST(c.word_of(b.model.settings) == w);
  });
}

BOOST_AUTO_TEST_CASE(a_settling_stage_choice_reaches_the_loader_the_engine_summary_and_docs) {
  choice_reaches(core::settle_choice_specs(), "analysis.settle",
                 [](const core::SettleChoiceSpec& c, const scene::BuiltScene& b, const std::string& w) {
                   BOOST_TEST(c.word_of(b.model.settings.settle) == w);
                 });
}

BOOST_AUTO_TEST_CASE(a_contact_choice_reaches_the_loader_the_contact_layer_summary_and_docs) {
  choice_reaches(contact::contact_choice_specs(), "analysis",
                 [](const contact::ContactChoiceSpec& c, const scene::BuiltScene& b, const std::string& w) {
                   BOOST_TEST(c.word_of(b.contact_settings) == w);
                 });
}

BOOST_AUTO_TEST_CASE(a_material_choice_reaches_the_loader_the_engine_summary_and_docs) {
  // Declared beside the material's properties (core/property_specs.hpp); the scene's
  // materials default to plane strain (scene::Material), the engine's to plane stress.
  const std::string table = scene::key_table_markdown("materials");
  const std::vector<scene::KeyInfo> keys = scene::declared_keys("materials");
  for (const core::MaterialChoiceSpec& c : core::material_choice_specs()) {
    BOOST_TEST_CONTEXT("materials." << c.name()) {
      const scene::KeyInfo& k = key_of(keys, c.name());
      BOOST_TEST((k.type == scene::KeyType::choice));
      BOOST_TEST(k.choices == c.words, boost::test_tools::per_element());
      const std::string row = fmt::format("| `{}` | – |  | {} | `{}` |\n", c.name(), c.meaning, c.word_of(scene::Material{}));
      BOOST_TEST(table.find(row) != std::string::npos, row);
      // Not given: the scene's default reaches the engine.
      BOOST_TEST(c.word_of(scene::build_scene(scene::parse_scene(kBaseScene, "given.yaml")).model.materials.at(0)) ==
                 c.word_of(scene::Material{}));
      const std::string given = "  rock: {density: 2600, young_modulus: 1.0e9, poisson_ratio: 0.25}\n";
      for (const std::string& word : c.words) {
        BOOST_TEST_CONTEXT("word " << word) {
          const std::string text =
              with(given, "  rock: {density: 2600, young_modulus: 1.0e9, poisson_ratio: 0.25, " + c.name() + ": " + word + "}\n");
          const scene::SceneDescription d = scene::parse_scene(text, "given.yaml");
          BOOST_TEST(c.word_of(d.materials.at(0)) == word);                              // the loader
          BOOST_TEST(c.word_of(scene::build_scene(d).model.materials.at(0)) == word);   // the engine
          const nlohmann::json inputs = nlohmann::json::parse(scene::scene_json_text(d));
          BOOST_TEST(inputs.at("materials").at("rock").at(c.name()).get<std::string>() == word);  // summary.json
        }
      }
      expect_error(with(given, "  rock: {density: 2600, young_modulus: 1.0e9, poisson_ratio: 0.25, " + c.name() + ": nonesuch}\n"),
                   7, 0, c.name(), "'nonesuch' is not one of: " + fmt::format("{}", fmt::join(c.words, ", ")));
    }
  }
}

BOOST_AUTO_TEST_CASE(gravity_reaches_the_loader_the_engine_summary_and_docs) {
  const core::VectorSettingSpec& g = core::gravity_spec();
  const scene::KeyInfo& k = key_of(scene::declared_keys("analysis"), g.name());
  BOOST_TEST((k.type == scene::KeyType::point));
  BOOST_TEST(k.unit == g.unit);
  BOOST_TEST(k.meaning == g.meaning);
  const scene::SceneDescription d = scene::parse_scene(with("  gravity: [0, -9.81]", "  gravity: [1.5, -7]"), "given.yaml");
  BOOST_TEST((d.analysis.*g.field)[0] == 1.5);
  BOOST_TEST((d.analysis.*g.field)[1] == -7.0);
  const scene::BuiltScene b = scene::build_scene(d);
  BOOST_TEST((b.model.settings.*g.field)[0] == 1.5);
  BOOST_TEST((b.model.settings.*g.field)[1] == -7.0);
  const nlohmann::json echoed = nlohmann::json::parse(scene::scene_json_text(d)).at("analysis").at("gravity");
  BOOST_TEST(echoed.at(0).get<double>() == 1.5);
  BOOST_TEST(echoed.at(1).get<double>() == -7.0);
}

BOOST_AUTO_TEST_CASE(every_declared_settle_number_is_checked_by_the_engine_under_its_scene_word) {
  // The engine refuses a value of the stage outside its declaration under settings.settle.NAME.
  for (const core::SettleSpec& s : core::settle_specs()) {
    BOOST_TEST_CONTEXT("settle." << s.name()) {
      const double bad = s.parameter.max < 1e300 ? s.parameter.max + 1.0 : -1.0;
      BOOST_TEST_REQUIRE(!s.admits(bad));
      core::Model m;
      core::BlockDef b;
      b.vertices = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
      m.blocks = {b};
      s.set(m.settings.settle, bad);
      try {
        core::Engine e(m);
        BOOST_ERROR("the engine took settle." << s.name() << " = " << bad);
      } catch (const core::ModelError& err) {
        BOOST_TEST(err.key() == "settings.settle." + s.name(), err.what());
        BOOST_TEST(err.message().find(s.range_text()) != std::string::npos, err.what());
      }
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()
