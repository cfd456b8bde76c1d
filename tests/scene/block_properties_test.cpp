// The properties of a block material, a bolt and the water (core/property_specs.hpp) and
// the scene's keys of `materials:`, `bolts:` and `water:`: each declared property is the
// key of its name with the declaration's unit, range, default and meaning; a value read
// from a scene file reaches the engine's Model (build_scene), `check`'s description and
// summary.json's inputs; a value outside the range is refused by the loader (file, line,
// key) and by the engine (ModelError, the key named). The reverse: every other key of
// these maps is one the scene keeps for itself (names, ends, surfaces, a law, `plane`).
#include <boost/test/unit_test.hpp>
#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include <map>
#include <set>

#include "declared_key_checks.hpp"
#include "test_support.hpp"
#include "rheodda/core/engine.hpp"
#include "rheodda/core/property_specs.hpp"
#include "rheodda/scene/build.hpp"
#include "rheodda/scene/describe.hpp"
#include "rheodda/scene/keys.hpp"
#include "rheodda/scene/loader.hpp"

using namespace rheodda;
using namespace rheodda::test;

namespace {

/// One value inside each declared property's range, other than its default, that hold
/// together (a pretension within the yield force); every declared property must have one.
const std::map<std::string, double> kGiven{
    {"density", 2700.0},        {"young_modulus", 2.0e9}, {"poisson_ratio", 0.3}, {"damping_ratio", 0.1},
    {"axial_stiffness", 2.0e6}, {"pretension", 100.0},    {"yield_force", 1.0e5}, {"rupture_elongation", 0.05},
    {"unit_weight", 9810.0}};

/// `keys` as a flow map's body: "density: 2700, young_modulus: 2e+09".
template <class S>
std::string given_keys(const std::vector<laws::SettingSpec<S>>& specs) {
  std::string out;
  for (const laws::SettingSpec<S>& s : specs) {
    BOOST_TEST_REQUIRE(kGiven.count(s.name()) == 1u, "no test value for the declared property " << s.name());
    const double v = kGiven.at(s.name());
    BOOST_TEST_REQUIRE(s.admits(v));
    BOOST_TEST_REQUIRE(v != *s.parameter.default_value);
    out += (out.empty() ? "" : ", ") + s.name() + ": " + scene::exact_number(v);
  }
  return out;
}

/// kBaseScene (dynamic: damping_ratio needs velocities) with the material `rock` given
/// `material` (line 8), a bolt (line 18) given `bolt` and water (line 19) given `water`.
std::string scene_with(const std::string& material, const std::string& bolt, const std::string& water) {
  return with("  rock: {density: 2600, young_modulus: 1.0e9, poisson_ratio: 0.25}", "  rock: {" + material + "}",
              with("  dt: 0.01", "  dt: 0.01\n  type: dynamic")) +
         "bolts:\n"                                                                                // 17
         "  - {name: b1, from: {point: [1.5, 2], block: top}, to: {fixed: [1.5, 4]}, " + bolt + "}\n"  // 18
         "water: {level: 0.5, " + water + "}\n";                                                   // 19
}

const std::string kMaterial = "density: 2600, young_modulus: 1.0e9, poisson_ratio: 0.25";
const std::string kBolt = "axial_stiffness: 1.0e6";
const std::string kWater = "unit_weight: 9810";

/// Each declaration of `specs` is the key of its name in `map` (`required`: the ones the
/// scene requires, whose default reads "required"); the keys of `map` that are not
/// declarations are `kept`.
template <class S>
void check_keys(const std::vector<laws::SettingSpec<S>>& specs, const std::string& map,
                const std::set<std::string>& required, const std::set<std::string>& kept) {
  const std::vector<scene::KeyInfo> keys = scene::declared_keys(map);
  std::set<std::string> declared;
  for (const laws::SettingSpec<S>& s : specs) {
    BOOST_TEST_CONTEXT(map << "." << s.name()) {
      declared.insert(s.name());
      const scene::KeyInfo& k = key_of(keys, s.name());
      BOOST_TEST((k.type == scene::KeyType::number));
      check_key_is_declaration(k, s.parameter);
      static const S defaults{};
      BOOST_TEST(s.value(defaults) == *s.parameter.default_value);  // the struct's default
      if (required.count(s.name()) != 0u) {
        BOOST_TEST(k.default_text.starts_with("required"));  // the loader's check: load_*.cpp
      } else {
        BOOST_TEST(k.default_text == s.default_text());
      }
    }
  }
  for (const std::string& key : scene::declared_key_names(map))
    BOOST_TEST((declared.count(key) + kept.count(key) == 1u), map << "." << key);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(block_properties)

BOOST_AUTO_TEST_CASE(every_declared_property_is_the_key_of_its_name_with_its_declaration) {
  BOOST_TEST_REQUIRE(core::material_specs().size() == 4u);
  BOOST_TEST_REQUIRE(core::bolt_specs().size() == 4u);
  BOOST_TEST_REQUIRE(core::water_specs().size() == 1u);
  check_keys(core::material_specs(), "materials", {"density", "young_modulus", "poisson_ratio"}, {"plane"});
  check_keys(core::bolt_specs(), "bolts", {"axial_stiffness"}, {"name", "from", "to", "law"});
  check_keys(core::water_specs(), "water", {"unit_weight"}, {"level", "surface", "level_history", "surface_history"});
}

BOOST_AUTO_TEST_CASE(a_value_read_reaches_the_engine_check_and_summary) {
  const scene::SceneDescription d = scene::parse_scene(
      scene_with(given_keys(core::material_specs()), given_keys(core::bolt_specs()), given_keys(core::water_specs())),
      "given.yaml");
  const scene::BuiltScene built = scene::build_scene(d);
  const nlohmann::json inputs = nlohmann::json::parse(scene::scene_json_text(d));
  const std::string check = scene::describe_scene(d);
  auto reaches = [&](const auto& specs, const auto& read, const auto& model, const std::string& map,
                     const nlohmann::json& echoed) {
    const std::vector<scene::KeyInfo> keys = scene::declared_keys(map);
    for (const auto& s : specs) {
      BOOST_TEST_CONTEXT(map << "." << s.name()) {
        const double v = kGiven.at(s.name());
        BOOST_TEST(s.value(read) == v);   // the loader
        BOOST_TEST(s.value(model) == v);  // the engine's Model
        if (key_of(keys, s.name()).echoed) BOOST_TEST(echoed.at(s.name()).template get<double>() == v);
        BOOST_TEST(check.find(s.name() + " " + fmt::format("{:g}", v)) != std::string::npos, check);
      }
    }
  };
  BOOST_TEST_REQUIRE(d.materials.size() == 1u);
  reaches(core::material_specs(), d.materials[0], built.model.materials[0], "materials",
          inputs.at("materials").at("rock"));
  BOOST_TEST_REQUIRE(d.bolts.size() == 1u);
  BOOST_TEST_REQUIRE(built.model.bolts.size() == 1u);
  reaches(core::bolt_specs(), d.bolts[0], built.model.bolts[0], "bolts", inputs.at("bolts").at(0));
  BOOST_TEST_REQUIRE(d.water.has_value());
  reaches(core::water_specs(), *d.water, built.model.water, "water", inputs.at("water"));
  BOOST_CHECK_NO_THROW(core::Engine(built.model));
}

BOOST_AUTO_TEST_CASE(out_of_range_is_refused_by_the_loader_and_the_engine) {
  // Below the lower bound, or on it where it is excluded: the loader names file, line
  // and key; the engine, given the value in a Model the scene built, the key.
  const scene::BuiltScene ok = scene::build_scene(scene::parse_scene(scene_with(kMaterial, kBolt, kWater), "ok.yaml"));
  auto refused = [&](const auto& spec, const std::string& scene_text, int line, const std::string& key,
                     const std::string& model_key, const auto& set_in_model) {
    BOOST_TEST_CONTEXT(key) {
      try {
        (void)scene::parse_scene(scene_text, "range.yaml");
        BOOST_ERROR("the scene took a value out of range");
      } catch (const scene::SceneError& err) {
        BOOST_TEST(err.key() == key, err.what());
        BOOST_TEST(err.line() == line, err.what());
        BOOST_TEST(std::string(err.what()).find("range.yaml:" + std::to_string(line) + ":") != std::string::npos);
      }
      core::Model m = ok.model;
      set_in_model(m);
      try {
        core::Engine e(m);
        BOOST_ERROR("the engine took a value out of range");
      } catch (const core::ModelError& err) {
        BOOST_TEST(err.key() == model_key, err.what());
        BOOST_TEST(err.message().find(spec.range_text()) != std::string::npos, err.what());
      }
    }
  };
  auto bad_of = [](const auto& s) { return s.parameter.min_exclusive ? s.parameter.min : s.parameter.min - 1.0; };
  for (const core::MaterialSpec& s : core::material_specs()) {
    const double bad = bad_of(s);
    BOOST_TEST_REQUIRE(!s.admits(bad));
    std::map<std::string, double> values{{"density", 2600.0}, {"young_modulus", 1.0e9}, {"poisson_ratio", 0.25}};
    values[s.name()] = bad;
    std::string given;
    for (const auto& [name, v] : values) given += (given.empty() ? "" : ", ") + name + ": " + scene::exact_number(v);
    refused(s, scene_with(given, kBolt, kWater), 8, "materials.rock." + s.name(), "materials[0]." + s.name(),
            [&](core::Model& m) { s.set(m.materials[0], bad); });
  }
  for (const core::BoltSpec& s : core::bolt_specs()) {
    if (s.parameter.min == std::numeric_limits<double>::lowest()) continue;  // any finite value (pretension)
    const double bad = bad_of(s);
    BOOST_TEST_REQUIRE(!s.admits(bad));
    refused(s, scene_with(kMaterial, kBolt + ", " + s.name() + ": " + scene::exact_number(bad), kWater), 18,
            "bolts[0]." + s.name(), "bolts[0]." + s.name(), [&](core::Model& m) { s.set(m.bolts[0], bad); });
  }
  for (const core::WaterSpec& s : core::water_specs()) {
    const double bad = bad_of(s);
    refused(s, scene_with(kMaterial, kBolt, s.name() + ": " + scene::exact_number(bad)), 19, "water." + s.name(),
            "water." + s.name(), [&](core::Model& m) { s.set(m.water, bad); });
  }
}

BOOST_AUTO_TEST_SUITE_END()
