// docs/reference/scene-format.md against the loader's schema, both ways: every key the
// loader reads is in a key table of the docs, every key a table documents is
// read. And the schema against the loader itself: each map's "valid keys here"
// (the list its MapReader refuses unknown keys with) is the schema's list.
//
// Why. A setting the engine has but a scene cannot reach, or a key the docs
// promise and the loader refuses (analysis.time_integration was both, issue 16),
// is only caught by reading the two side by side; this test does it on every build.
//
// How the docs are read: in each section named in kSectionPath, every table whose
// first header is `key` is a key table; each row's first cell holds the key(s) in
// backticks (`units.length` counts as `length`). A row whose meaning starts with
// `{a, b, ...}` (blocks' `rectangle` and `grid`) also documents the keys of that
// sub-map. The points section's table (first header `list`) gives per list the
// backticked keys of its second cell (`force: [fx, fy]` counts as `force`).
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <functional>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "test_support.hpp"
#include "rheodda/core/contact_solve.hpp"
#include "rheodda/core/integrator.hpp"
#include "rheodda/core/solver.hpp"
#include "rheodda/laws/registry.hpp"
#include "rheodda/scene/assemble.hpp"
#include "rheodda/scene/build.hpp"
#include "rheodda/scene/describe.hpp"
#include "rheodda/scene/keys.hpp"
#include "rheodda/scene/loader.hpp"

using namespace rheodda;
using namespace rheodda::test;

namespace {

using KeyTables = std::map<std::string, std::set<std::string>>;  ///< map path -> keys

/// Schema path of the key table of each section of docs/reference/scene-format.md.
const std::map<std::string, std::string> kSectionPath{
    {"Top level", ""},           {"Units", "units"},           {"analysis", "analysis"},
    {"analysis.settle", "analysis.settle"},
    {"materials", "materials.*"}, {"joint_sets", "joint_sets.*"}, {"law", "joint_sets.*.law"},
    {"blocks", "blocks[*]"},
    {"rock_mass", "rock_mass"},   {"rock_mass.joint_sets", "rock_mass.joint_sets[*]"},
    {"rock_mass.traces", "rock_mass.traces[*]"},
    {"water", "water"},           {"water.surface_history", "water.surface_history[*]"},
    {"stages", "stages[*]"},      {"stages.add_fixed_points", "stages[*].add_fixed_points[*]"},
    {"stages.add_loads", "stages[*].add_loads[*]"}, {"stages.joint_sets", "stages[*].joint_sets.*"},
    {"stages.joint_sets.law", "stages[*].joint_sets.*.law"}, {"bolts", "bolts[*]"},
    {"blocks.rectangle", "blocks[*].rectangle"}, {"blocks.grid", "blocks[*].grid"},
    {"fixed_points", "fixed_points[*]"}, {"loads", "loads[*]"}, {"measurement_points", "measurement_points[*]"},
    {"bolts.from", "bolts[*].from"}, {"bolts.to", "bolts[*].to"},
    {"stages.add_bolts", "stages[*].add_bolts[*]"},
    {"stages.remove_blocks", "stages[*].remove_blocks"}, {"stages.analysis", "stages[*].analysis"},
};
/// The section whose `list` table documents the keys of each point list.
const std::string kPointsSection = "fixed_points, loads, measurement_points";

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t") - a + 1);
}

/// Cells of a table row `| a | b |` (no escaped bars in this file).
std::vector<std::string> cells(const std::string& row) {
  std::vector<std::string> out;
  std::stringstream in(row.substr(1));
  std::string c;
  while (std::getline(in, c, '|')) out.push_back(trim(c));
  if (!out.empty() && out.back().empty()) out.pop_back();
  return out;
}

/// The backticked spans of a cell, in order.
std::vector<std::string> code_spans(const std::string& cell) {
  std::vector<std::string> out;
  static const std::regex code("`([^`]*)`");
  for (std::sregex_iterator it(cell.begin(), cell.end(), code), end; it != end; ++it) out.push_back((*it)[1]);
  return out;
}

/// The key tables of the document, by schema path.
KeyTables documented_keys(const std::string& text) {
  KeyTables doc;
  std::istringstream in(text);
  std::string line, section;
  std::vector<std::string> header;  // of the table being read; empty outside tables
  bool in_code_block = false;
  while (std::getline(in, line)) {
    if (line.rfind("```", 0) == 0) in_code_block = !in_code_block;
    if (in_code_block) continue;
    if (line.rfind("#", 0) == 0) {
      section = trim(line.substr(line.find_first_not_of('#')));
      continue;
    }
    if (line.rfind("|", 0) != 0) {
      header.clear();
      continue;
    }
    const std::vector<std::string> row = cells(line);
    if (header.empty()) {
      header = row;
      continue;
    }
    if (!row.empty() && row[0].find_first_not_of("-: ") == std::string::npos) continue;  // |---|---|
    BOOST_TEST_INFO("docs/reference/scene-format.md, section '" << section << "', row: " << line);
    if (header[0] == "key") {
      const auto path = kSectionPath.find(section);
      BOOST_TEST_REQUIRE((path != kSectionPath.end()), "a key table in a section the test does not know");
      const std::vector<std::string> keys = code_spans(row[0]);
      BOOST_TEST_REQUIRE(!keys.empty(), "a key table row without a `key`");
      const auto meaning = std::find(header.begin(), header.end(), "meaning") - header.begin();
      BOOST_TEST_REQUIRE(static_cast<std::size_t>(meaning) < row.size(), "a key table without a meaning column");
      for (std::string key : keys) {
        key = key.substr(key.find_last_of('.') + 1);  // `units.length` -> length
        doc[path->second].insert(key);
        // `{x, y, width, ...}`: the keys of the sub-map this key holds.
        const std::string& m = row[static_cast<std::size_t>(meaning)];
        if (m.rfind("`{", 0) == 0) {
          const std::string inner = m.substr(2, m.find('}') - 2);
          std::stringstream words(inner);
          std::string w;
          const std::string sub = path->second + "." + key;
          doc[sub];  // a sub-map with no keys documented still shows up
          while (std::getline(words, w, ',')) doc[sub].insert(trim(w));
        }
      }
    } else if (header[0] == "list") {
      BOOST_TEST_REQUIRE(section == kPointsSection);
      const std::vector<std::string> list = code_spans(row[0]);
      BOOST_TEST_REQUIRE(list.size() == 1u);
      BOOST_TEST_REQUIRE(row.size() >= 2u);
      static const std::regex word("^[a-z_]+");
      auto& keys = doc[list[0] + "[*]"];
      for (const std::string& span : code_spans(row[1])) {
        std::smatch m;
        BOOST_TEST_REQUIRE(std::regex_search(span, m, word), "`" << span << "` does not start with a key");
        keys.insert(m.str());
      }
    }
  }
  return doc;
}

KeyTables schema_keys() {
  KeyTables out;
  for (const auto& m : scene::scene_schema()) {
    BOOST_TEST(!out.count(m.path), "schema path '" << m.path << "' listed twice");
    out[m.path].insert(m.keys.begin(), m.keys.end());
    BOOST_TEST(out[m.path].size() == m.keys.size(), "schema path '" << m.path << "' lists a key twice");
  }
  return out;
}

std::string dotted(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

/// The keys listed after "valid keys here: " in an unknown-key error of `text`.
std::vector<std::string> valid_keys_reported(const std::string& text) {
  try {
    (void)scene::parse_scene(text, "probe.yaml");
  } catch (const scene::SceneError& e) {
    const std::string m = e.message();
    const std::string tag = "valid keys here: ";
    BOOST_TEST_REQUIRE(m.find("unknown key 'bogus_key'") != std::string::npos, "error: " << e.what());
    std::vector<std::string> keys;
    std::stringstream in(m.substr(m.find(tag) + tag.size()));
    std::string k;
    while (std::getline(in, k, ',')) keys.push_back(trim(k));
    return keys;
  }
  BOOST_ERROR("the unknown key 'bogus_key' was accepted");
  return {};
}

}  // namespace

BOOST_AUTO_TEST_SUITE(scene_schema)

BOOST_AUTO_TEST_CASE(every_key_the_loader_reads_is_documented_and_every_documented_key_is_read) {
  const KeyTables doc = documented_keys(read_text(source_path("docs/reference/scene-format.md")));
  const KeyTables schema = schema_keys();
  BOOST_TEST_REQUIRE(doc.size() >= 10u, "docs/reference/scene-format.md: key tables not found");
  for (const auto& [path, keys] : schema) {
    const auto d = doc.find(path);
    BOOST_TEST((d != doc.end()), "the loader reads the map '" << path
                                   << "' but docs/reference/scene-format.md has no key table for it");
    if (d == doc.end()) continue;
    for (const auto& k : keys)
      BOOST_TEST(d->second.count(k) == 1u,
                 "the loader reads '" << dotted(path, k) << "' but docs/reference/scene-format.md does not document it");
  }
  for (const auto& [path, keys] : doc) {
    const auto s = schema.find(path);
    BOOST_TEST((s != schema.end()), "docs/reference/scene-format.md documents a map '" << path << "' the loader does not read");
    if (s == schema.end()) continue;
    for (const auto& k : keys)
      BOOST_TEST(s->second.count(k) == 1u,
                 "docs/reference/scene-format.md documents '" << dotted(path, k) << "' but the loader refuses it");
  }
}

BOOST_AUTO_TEST_CASE(the_schema_is_the_list_each_map_refuses_unknown_keys_with) {
  // Per schema path: kBaseScene with an unknown key `bogus_key` put into one map
  // of that path. Every path of the schema must have one here.
  const std::map<std::string, std::string> probes{
      {"", "bogus_key: 1\n" + kBaseScene},
      {"units", with("units: {length: m,", "units: {bogus_key: 1, length: m,")},
      {"analysis", with("  duration: 1\n", "  bogus_key: 1\n  duration: 1\n")},
      {"analysis.settle", with("  duration: 1\n", "  duration: 1\n  settle: {bogus_key: 1, until: 0.1, dt: 0.01}\n")},
      {"materials.*", with("rock: {density", "rock: {bogus_key: 1, density")},
      {"joint_sets.*", with("bedding: {friction_angle: 30}", "bedding: {bogus_key: 1, friction_angle: 30}")},
      {"joint_sets.*.law", with("{name: burgers,", "{name: burgers, bogus_key: 1,")},
      {"blocks[*]", with("{name: base,", "{bogus_key: 1, name: base,")},
      {"blocks[*].rectangle", with("rectangle: {x: 0,", "rectangle: {bogus_key: 1, x: 0,")},
      {"blocks[*].grid", with("rectangle: {x: 0, y: 0, width: 4, height: 1}",
                              "grid: {bogus_key: 1, x: 0, y: 0, width: 4, height: 1, columns: 1, rows: 1}")},
      {"fixed_points[*]", kBaseScene + "fixed_points:\n  - {bogus_key: 1, point: [0, 0]}\n"},
      {"loads[*]", kBaseScene + "loads:\n  - {bogus_key: 1, point: [1.5, 2], force: [0, 0]}\n"},
      {"measurement_points[*]", with("{name: p,", "{bogus_key: 1, name: p,")},
      {"bolts[*]", kBaseScene + "bolts:\n  - {bogus_key: 1, name: b}\n"},
      {"bolts[*].from", kBaseScene + "bolts:\n  - {name: b, from: {bogus_key: 1}}\n"},
      {"bolts[*].to", kBaseScene + "bolts:\n  - {name: b, from: {point: [1.5, 2]}, to: {bogus_key: 1}}\n"},
      {"bolts[*].law", kBaseScene + "bolts:\n  - {name: b, from: {point: [1.5, 2]}, to: {fixed: [1.5, 4]}, "
                                    "law: {name: burgers, bogus_key: 1}}\n"},
      {"rock_mass", kBaseScene + "rock_mass: {bogus_key: 1, region: [[0, 5], [4, 5], [4, 8], [0, 8]]}\n"},
      {"rock_mass.joint_sets[*]", kBaseScene + "rock_mass: {region: [[0, 5], [4, 5], [4, 8], [0, 8]], "
                                                "boundary_joint_set: bedding, joint_sets: [{bogus_key: 1}]}\n"},
      {"rock_mass.traces[*]", kBaseScene + "rock_mass: {region: [[0, 5], [4, 5], [4, 8], [0, 8]], "
                                            "boundary_joint_set: bedding, traces: [{bogus_key: 1}]}\n"},
      {"water", kBaseScene + "water: {bogus_key: 1, unit_weight: 9810, level: 1}\n"},
      {"water.surface_history[*]", kBaseScene + "water: {unit_weight: 9810, surface_history: [{bogus_key: 1}]}\n"},
      {"stages[*]", kBaseScene + "stages:\n  - {bogus_key: 1, name: a, at: 0.5}\n"},
      {"stages[*].remove_blocks", kBaseScene + "stages:\n  - {name: a, at: 0.5, remove_blocks: {bogus_key: 1}}\n"},
      {"stages[*].add_fixed_points[*]",
       kBaseScene + "stages:\n  - {name: a, at: 0.5, add_fixed_points: [{bogus_key: 1}]}\n"},
      {"stages[*].add_loads[*]", kBaseScene + "stages:\n  - {name: a, at: 0.5, add_loads: [{bogus_key: 1}]}\n"},
      {"stages[*].joint_sets.*",
       kBaseScene + "stages:\n  - {name: a, at: 0.5, joint_sets: {bedding: {bogus_key: 1}}}\n"},
      {"stages[*].joint_sets.*.law",
       kBaseScene + "stages:\n  - {name: a, at: 0.5, joint_sets: {fault: {law: {name: burgers, bogus_key: 1}}}}\n"},
      {"stages[*].analysis", kBaseScene + "stages:\n  - {name: a, at: 0.5, analysis: {bogus_key: 1}}\n"},
      {"stages[*].add_bolts[*]", kBaseScene + "stages:\n  - {name: a, at: 0.5, add_bolts: [{bogus_key: 1}]}\n"},
      {"stages[*].add_bolts[*].from",
       kBaseScene + "stages:\n  - {name: a, at: 0.5, add_bolts: [{name: b, from: {bogus_key: 1}}]}\n"},
      {"stages[*].add_bolts[*].to", kBaseScene + "stages:\n  - {name: a, at: 0.5, add_bolts: [{name: b, from: "
                                                 "{point: [1.5, 2], block: top}, to: {bogus_key: 1}}]}\n"},
      {"stages[*].add_bolts[*].law",
       kBaseScene + "stages:\n  - {name: a, at: 0.5, add_bolts: [{name: b, from: {point: [1.5, 2], block: top}, "
                    "to: {fixed: [1.5, 4]}, law: {name: burgers, bogus_key: 1}}]}\n"},
      {"stages[*].water",
       kBaseScene + "stages:\n  - {name: a, at: 0.5, water: {bogus_key: 1, unit_weight: 9810, level: 1}}\n"},
  };
  for (const auto& m : scene::scene_schema()) {
    BOOST_TEST_CONTEXT("schema path '" << m.path << "'") {
      const auto probe = probes.find(m.path);
      BOOST_TEST_REQUIRE((probe != probes.end()), "no probe scene for this map: add one above");
      std::vector<std::string> expected = m.keys;
      if (m.path.ends_with("joint_sets.*.law") || m.path.ends_with("bolts[*].law"))  // the law map also takes the law's parameters
        for (const auto& p : laws::LawRegistry::builtin().find("burgers")->parameters) expected.push_back(p.name);
      BOOST_TEST(valid_keys_reported(probe->second) == expected, boost::test_tools::per_element());
    }
  }
  BOOST_TEST(probes.size() == scene::scene_schema().size(), "a probe for a map the schema does not have");
}

BOOST_AUTO_TEST_CASE(the_docs_key_tables_are_the_declarations) {
  // docs/reference/scene-format.md holds, between its keys-MAP markers, what `rheodda keys
  // --markdown MAP` prints (scripts/scene-format-tables.sh writes it).
  const std::string doc = read_text(source_path("docs/reference/scene-format.md"));
  for (const scene::DeclaredMap& m : scene::declared_maps()) {
    const std::string& map = m.name;
    const std::string begin = "<!-- keys-" + map + ":begin -->\n", end = "<!-- keys-" + map + ":end -->";
    const auto b = doc.find(begin), e = doc.find(end);
    BOOST_TEST_REQUIRE((b != std::string::npos && e != std::string::npos), "no markers for " << map);
    BOOST_TEST(doc.substr(b + begin.size(), e - b - begin.size()) == scene::key_table_markdown(map),
               "docs/reference/scene-format.md's table of " << map << " is not the declarations': run "
                                                     "scripts/scene-format-tables.sh");
  }
}

namespace {

double g_dummy = 0.5;  ///< where the dummy key of the test below is read to

/// Declares `dummy_margin` (a number in (0, 1] [length], default 0.5) in the map `map`
/// of the typed list `list`, read into g_dummy; what it returns takes it back.
template <class E>
std::function<void()> declare_dummy(std::vector<scene::EntryKey<E>>& list, const std::string& map) {
  scene::EntryKey<E> k;
  k.map = map;
  k.name = "dummy_margin";
  k.type = scene::KeyType::number;
  k.unit = "length";
  k.range = {0.0, true, 1.0, false};
  k.default_text = "0.5";
  k.meaning = "a key only this test declares";
  k.get = [](const E&) -> scene::KeyValue { return g_dummy; };
  k.set = [](E&, const scene::KeyValue& v) { g_dummy = std::get<double>(v); };
  list.push_back(k);
  return [&list] { list.pop_back(); };
}

/// One declared map of the test below: how to declare the dummy key in it, a valid scene
/// giving it (`D` stands for the key and its value), and which of `check` and
/// summary.json describe the map from its declarations.
struct DummyCase {
  std::function<std::function<void()>()> declare;
  std::string scene;
  bool in_check = false;
  bool in_summary = false;
};

const std::string kStage = "stages:\n  - {name: a, at: 0.5, ";
const std::string kBolt = "bolts:\n  - {name: b, from: {point: [1.5, 1.5]}, to: {fixed: [1.5, 4]}, axial_stiffness: 1e6";
const std::string kRockMass = "rock_mass: {region: [[0, 5], [4, 5], [4, 8], [0, 8]], boundary_joint_set: bedding";

/// Per declared map (scene::declared_maps()), its case.
std::map<std::string, DummyCase> dummy_cases() {
  using namespace scene;
  auto dummy = [](auto& list, const std::string& map) { return [&list, map] { return declare_dummy(list, map); }; };
  return {
      {"top", {dummy(top_keys(), "top"), "D\n" + kBaseScene, false, true}},
      {"units", {dummy(units_keys(), "units"), with("units: {length: m,", "units: {D, length: m,"), true, true}},
      {"analysis", {dummy(analysis_keys(), "analysis"), with("  duration: 1\n", "  duration: 1\n  D\n"), true, true}},
      {"analysis.settle",
       {dummy(analysis_keys(), "analysis.settle"),
        with("  duration: 1\n", "  duration: 1\n  settle: {D, until: 0.1, dt: 0.01}\n"), true, true}},
      {"materials", {dummy(material_keys(), "materials"), with("rock: {density", "rock: {D, density"), true, true}},
      {"joint_sets",
       {dummy(joint_set_keys(), "joint_sets"), with("bedding: {friction_angle: 30}", "bedding: {D, friction_angle: 30}"),
        true, true}},
      {"law", {dummy(law_keys(), "law"), with("{name: burgers,", "{name: burgers, D,"), false, true}},
      {"blocks", {dummy(block_keys(), "blocks"), with("{name: base,", "{D, name: base,"), false, true}},
      {"blocks.rectangle", {dummy(rectangle_keys(), "blocks.rectangle"), with("rectangle: {x: 0,", "rectangle: {D, x: 0,")}},
      {"blocks.grid",
       {dummy(grid_keys(), "blocks.grid"),
        with("rectangle: {x: 0, y: 0, width: 4, height: 1}", "grid: {D, x: 0, y: 0, width: 4, height: 1, columns: 1, rows: 1}")}},
      {"rock_mass", {dummy(rock_mass_keys(), "rock_mass"), kBaseScene + kRockMass + ", D}\n", false, true}},
      {"rock_mass.joint_sets",
       {dummy(rock_mass_joint_set_keys(), "rock_mass.joint_sets"),
        kBaseScene + kRockMass + ", joint_sets: [{D, joint_set: bedding, dip: 0, spacing: 1}]}\n", false, true}},
      {"rock_mass.traces",
       {dummy(rock_mass_trace_keys(), "rock_mass.traces"),
        kBaseScene + kRockMass + ", traces: [{D, joint_set: fault, from: [0, 6.5], to: [4, 6.5]}]}\n", false, true}},
      {"fixed_points",
       {dummy(fixed_point_keys(), "fixed_points"), kBaseScene + "fixed_points:\n  - {D, point: [1.5, 1.5]}\n", true, true}},
      {"loads",
       {dummy(load_keys(), "loads"), kBaseScene + "loads:\n  - {D, point: [1.5, 1.5], force: [0, 1]}\n", true, true}},
      {"measurement_points",
       {dummy(measurement_point_keys(), "measurement_points"), with("{name: p,", "{D, name: p,"), true, true}},
      {"water", {dummy(water_keys(), "water"), kBaseScene + "water: {D, unit_weight: 9810, level: 1}\n", true, true}},
      {"water.surface_history",
       {dummy(water_sample_keys(), "water.surface_history"),
        kBaseScene + "water: {unit_weight: 9810, surface_history: [{D, time: 0, surface: [[-1, 1], [5, 1]]}]}\n", false,
        true}},
      {"bolts", {dummy(bolt_keys(), "bolts"), kBaseScene + kBolt + ", D}\n", true, true}},
      {"bolts.from",
       {dummy(bolt_end_keys(), "bolts.from"), with("from: {point: [1.5, 1.5]}", "from: {D, point: [1.5, 1.5]}",
                                                   kBaseScene + kBolt + "}\n"),
        false, true}},
      {"bolts.to",
       {dummy(bolt_to_keys(), "bolts.to"), with("to: {fixed: [1.5, 4]}", "to: {D, fixed: [1.5, 4]}", kBaseScene + kBolt + "}\n"),
        false, true}},
      {"stages", {dummy(stage_keys(), "stages"), kBaseScene + kStage + "D, settle: false}\n", false, true}},
      {"stages.remove_blocks",
       {dummy(stage_remove_blocks_keys(), "stages.remove_blocks"),
        with("  - {name: p, point: [1.5, 1.5]}\n", "  - {name: p, point: [1.5, 0.5]}\n") + kStage +
            "remove_blocks: {D, names: [top]}}\n"}},
      {"stages.add_fixed_points",
       {dummy(stage_fixed_point_keys(), "stages.add_fixed_points"),
        kBaseScene + kStage + "add_fixed_points: [{D, point: [1.5, 1.5], block: top}]}\n", false, true}},
      {"stages.add_loads",
       {dummy(stage_load_keys(), "stages.add_loads"),
        kBaseScene + kStage + "add_loads: [{D, point: [1.5, 1.5], block: top, force: [0, 1]}]}\n", false, true}},
      {"stages.joint_sets",
       {dummy(stage_joint_set_keys(), "stages.joint_sets"),
        kBaseScene + kStage + "joint_sets: {bedding: {D, friction_angle: 20}}}\n", false, true}},
      {"stages.analysis",
       {dummy(stage_analysis_keys(), "stages.analysis"), kBaseScene + kStage + "analysis: {D, type: dynamic}}\n", false,
        true}},
  };
}

/// `text` with its `D` (the one capital D of every case's scene) replaced by `key_value`.
std::string with_dummy(const std::string& text, const std::string& key_value) {
  return with("D", key_value, text);
}

}  // namespace

BOOST_AUTO_TEST_CASE(a_key_declared_once_in_any_map_reaches_the_loader_the_schema_the_docs_check_and_summary) {
  // One declaration, nothing else, in each declared map in turn: the key must then be
  // read (with its range and unit in the message, at its line), be in the schema and the
  // docs table, and, for the maps `check` and summary.json describe from their
  // declarations, in `check`'s description and in summary.json's inputs.
  const std::map<std::string, DummyCase> cases = dummy_cases();
  for (const scene::DeclaredMap& m : scene::declared_maps()) {
    BOOST_TEST_CONTEXT("declared map '" << m.name << "'") {
      const auto c = cases.find(m.name);
      BOOST_TEST_REQUIRE((c != cases.end()), "no case for this map: add one to dummy_cases()");
      const std::function<void()> undeclare = c->second.declare();
      struct Undeclare {
        const std::function<void()>& f;
        ~Undeclare() { f(); }
      } guard{undeclare};

      g_dummy = 0.5;
      const scene::SceneDescription s = scene::parse_scene(with_dummy(c->second.scene, "dummy_margin: 0.25"), "dummy.yaml");
      BOOST_TEST(g_dummy == 0.25, "the loader did not read it");
      const std::string bad = with_dummy(c->second.scene, "dummy_margin: 1.5");
      try {
        (void)scene::parse_scene(bad, "dummy.yaml");
        BOOST_ERROR("dummy_margin: 1.5 was accepted");
      } catch (const scene::SceneError& e) {
        BOOST_TEST(e.key().ends_with("dummy_margin"), e.what());
        BOOST_TEST(e.line() == static_cast<int>(std::count(bad.begin(), bad.begin() + static_cast<long>(bad.find("dummy_margin")), '\n')) + 1);
        BOOST_TEST(e.message().find("out of range (0, 1] [length]") != std::string::npos, e.what());
      }
      for (const std::string& path : m.schema_paths) {
        bool in_schema = false;
        for (const auto& sm : scene::scene_schema())
          if (sm.path == path) in_schema = std::find(sm.keys.begin(), sm.keys.end(), "dummy_margin") != sm.keys.end();
        BOOST_TEST(in_schema, "not in the schema at " << path);
      }
      BOOST_TEST(scene::key_table_markdown(m.name).find("| `dummy_margin` | length | (0, 1] | a key only this test declares | 0.5 |") !=
                 std::string::npos);
      if (c->second.in_check)
        BOOST_TEST(scene::describe_scene(s).find("dummy_margin 0.25 m") != std::string::npos, scene::describe_scene(s));
      if (c->second.in_summary)
        BOOST_TEST(scene::scene_json_text(s).find("\"dummy_margin\":0.25") != std::string::npos, scene::scene_json_text(s));
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_CASE(every_registered_contact_solve_is_a_word_the_scene_reads_and_the_engine_makes) {
  // A contact solve is one row of core::contact_solves() (core/contact_solve.hpp): the scene's
  // `contact_solver` key takes its words from the rows, in their order, reads each word into its
  // method, build_scene hands the method to the engine, and the engine makes it from the row.
  const auto& keys = scene::analysis_keys();
  const auto key = std::find_if(keys.begin(), keys.end(), [](const scene::KeySpec& k) {
    return k.map == "analysis" && k.name == "contact_solver";
  });
  BOOST_TEST_REQUIRE((key != keys.end()));
  std::vector<std::string> words;
  for (const core::ContactSolveEntry& e : core::contact_solves()) words.emplace_back(e.word);
  BOOST_TEST(key->choices == words, boost::test_tools::per_element());
  for (const core::ContactSolveEntry& e : core::contact_solves()) {
    const std::string text = with("  dt: 0.01", "  dt: 0.01\n  contact_solver: " + std::string(e.word));
    const scene::BuiltScene built = scene::build_scene(scene::parse_scene(text, "solve.yaml"));
    BOOST_TEST((built.model.settings.contact_solver == e.method), e.word);
    BOOST_TEST(core::make_contact_solve(e.method) != nullptr);
  }
}

BOOST_AUTO_TEST_CASE(every_registered_integrator_is_a_word_the_scene_reads_and_the_engine_steps_with) {
  // An integrator is one row of core::integrators() (core/integrator.hpp): the scene's `integrator`
  // key takes its words from the rows, in their order, and reads each word into its method;
  // build_scene hands the engine the method, a choice between the others (a row without a trial of
  // its own: `automatic`) resolved to one that has a trial; the engine refuses an unresolved
  // choice, naming the setting, and takes a dynamic step with each.
  const auto& keys = scene::analysis_keys();
  const auto key = std::find_if(keys.begin(), keys.end(), [](const scene::KeySpec& k) {
    return k.map == "analysis" && k.name == "integrator";
  });
  BOOST_TEST_REQUIRE((key != keys.end()));
  std::vector<std::string> words;
  for (const core::IntegratorEntry& e : core::integrators()) words.emplace_back(e.word);
  BOOST_TEST(key->choices == words, boost::test_tools::per_element());
  for (const core::IntegratorEntry& e : core::integrators()) {
    BOOST_TEST_CONTEXT(e.word) {
      const std::string text = with("  dt: 0.01", "  dt: 0.01\n  type: dynamic\n  integrator: " + std::string(e.word));
      const scene::SceneDescription s = scene::parse_scene(text, "integrator.yaml");
      BOOST_TEST((s.analysis.integrator == e.method));
      const scene::BuiltScene built = scene::build_scene(s);
      const core::Integrator used = built.model.settings.integrator;
      BOOST_TEST(core::integrator_entry(used).dynamic_trial != nullptr);
      if (e.dynamic_trial) {
        BOOST_TEST((used == e.method));
      } else {
        core::Model unresolved = built.model;
        unresolved.settings.integrator = e.method;
        BOOST_CHECK_EXCEPTION(core::Engine{unresolved}, core::ModelError, [&](const core::ModelError& err) {
          return err.key() == "settings.integrator" &&
                 std::string(err.what()).find(std::string(e.word) + " chooses between the integrators") !=
                     std::string::npos;
        });
      }
      const scene::AssembledScene a = scene::assemble_scene(s, built);
      const core::StepReport rep = a.engine->step();
      BOOST_TEST(rep.time > 0.0);
      BOOST_TEST((rep.cycles > 0) == (used == core::Integrator::explicit_step));  // only the explicit step cycles
    }
  }
}

BOOST_AUTO_TEST_CASE(every_registered_linear_solver_is_a_word_the_scene_reads_and_hands_the_engine) {
  // A linear solver is one row of core::linear_solvers() (core/solver.hpp): the scene's `solver`
  // key takes its words from the rows, in their order, reads each word into its method, and
  // build_scene hands the method to the engine.
  const auto& keys = scene::analysis_keys();
  const auto key = std::find_if(keys.begin(), keys.end(), [](const scene::KeySpec& k) {
    return k.map == "analysis" && k.name == "solver";
  });
  BOOST_TEST_REQUIRE((key != keys.end()));
  std::vector<std::string> words;
  for (const core::LinearSolverEntry& e : core::linear_solvers()) words.emplace_back(e.word);
  BOOST_TEST(key->choices == words, boost::test_tools::per_element());
  for (const core::LinearSolverEntry& e : core::linear_solvers()) {
    const std::string text = with("  dt: 0.01", "  dt: 0.01\n  solver: " + std::string(e.word));
    const scene::BuiltScene built = scene::build_scene(scene::parse_scene(text, "solver.yaml"));
    BOOST_TEST((built.model.settings.solver == e.method), e.word);
  }
}
