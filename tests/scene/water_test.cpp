// `water:` in a scene (docs/reference/water.md; docs/reference/scene-format.md, "water"): the four
// forms of the phreatic surface are read and built, every bad input is refused
// with file:line:col and its key, a drained scene runs bit for bit as one
// without water, and examples/water-plane-failure.yaml fails when the tension
// crack's water reaches Hoek & Bray's critical depth, with the contacts'
// pressure in contacts.csv.
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include "run_support.hpp"
#include "rheodda/scene/build.hpp"
#include "rheodda/scene/describe.hpp"

using namespace rheodda;
using namespace rheodda::test;

namespace {

namespace fs = std::filesystem;

/// The data rows of a CSV file (the units comment and the header dropped), split in cells.
std::vector<std::vector<std::string>> csv_rows(const fs::path& file, std::string* header = nullptr) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);  // # units
  std::getline(in, line);
  if (header) *header = line;
  std::vector<std::vector<std::string>> rows;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream s(line);
    std::string c;
    while (std::getline(s, c, ',')) cells.push_back(c);
    rows.push_back(cells);
  }
  return rows;
}

/// The text of a CSV file without its last column.
std::string without_last_column(const std::string& text) {
  std::istringstream in(text);
  std::string line, out;
  while (std::getline(in, line)) out += (line.rfind('#', 0) == 0 ? line : line.substr(0, line.rfind(','))) + "\n";
  return out;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(scene_water)

BOOST_AUTO_TEST_CASE(the_four_forms_of_the_surface_are_read_and_built_for_the_engine) {
  // kBaseScene's blocks span x = 0 .. 4.
  {
    const auto s = scene::parse_scene(kBaseScene + "water: {unit_weight: 9810, level: 1.5}\n", "level.yaml");
    BOOST_TEST_REQUIRE(s.water.has_value());
    BOOST_TEST(s.water->unit_weight == 9810.0);
    const core::Water w = scene::build_scene(s).model.water;
    BOOST_TEST(w.unit_weight == 9810.0);
    BOOST_TEST_REQUIRE(w.history.size() == 1u);
    BOOST_TEST(core::water_level_at(w, -10.0, 0.0) == 1.5);
    BOOST_TEST(core::water_level_at(w, 2.0, 5.0) == 1.5);
    BOOST_TEST(scene::describe_scene(s).find("water: unit_weight 9810 N/m^3, level 1.5 m") != std::string::npos);
  }
  {
    const auto s = scene::parse_scene(kBaseScene + "water: {unit_weight: 10, surface: [[-1, 2], [1, 3], [5, 1]]}\n",
                                      "surface.yaml");
    const core::Water w = scene::build_scene(s).model.water;
    BOOST_TEST(core::water_level_at(w, 0.0, 0.0) == 2.5);
    BOOST_TEST(core::water_level_at(w, 3.0, 0.0) == 2.0);
  }
  {
    // A drawdown from 3 m to 0.5 m over 10 s and a refill to 2 m at 20 s.
    const auto s = scene::parse_scene(
        kBaseScene + "water: {unit_weight: 9810, level_history: [[0, 3], [10, 0.5], [20, 2]]}\n", "drawdown.yaml");
    const core::Water w = scene::build_scene(s).model.water;
    BOOST_TEST(core::water_level_at(w, 1.0, 5.0) == 1.75);
    BOOST_TEST(core::water_level_at(w, 1.0, 15.0) == 1.25);
    BOOST_TEST(core::water_level_at(w, 1.0, 30.0) == 2.0);
    BOOST_TEST(scene::describe_scene(s).find("level_history of 3 samples") != std::string::npos);
  }
  {
    const auto s = scene::parse_scene(kBaseScene +
                                          "water:\n  unit_weight: 9810\n  surface_history:\n"
                                          "    - {time: 0, surface: [[0, 1], [4, 1]]}\n"
                                          "    - {time: 2, surface: [[-1, 3], [2, 3], [4, 1]]}\n",
                                      "surfaces.yaml");
    const core::Water w = scene::build_scene(s).model.water;
    BOOST_TEST(core::water_level_at(w, 1.0, 1.0) == 2.0);
    BOOST_TEST(core::water_level_at(w, 3.0, 1.0) == 1.5);
  }
  // Without `water:` the model has none.
  BOOST_TEST(!scene::build_scene(scene::parse_scene(kBaseScene, "dry.yaml")).model.water.active());
}

BOOST_AUTO_TEST_CASE(bad_water_is_refused_with_file_line_column_and_key) {
  const std::string base = kBaseScene + "water:\n";  // line 16 is `water:`, 17 onwards its keys
  expect_error_at(base + "  unit_weight: -9810\n  level: 1\n", 17, "-9810", "water.unit_weight", "out of range");
  expect_error_at(base + "  unit_weight: 0\n  level: 1\n", 17, "0", "water.unit_weight", "out of range");
  expect_error_at(base + "  level: 1\n", 17, "level", "water.unit_weight", "missing required key 'unit_weight'");
  expect_error_at(base + "  unit_weight: 9810\n  levle: 1\n", 18, "levle", "water.levle", "did you mean 'level'?");
  expect_error_at(base + "  unit_weight: 9810\n", 17, "unit_weight", "water", "missing the phreatic surface");
  expect_error_at(base + "  unit_weight: 9810\n  level: 1\n  surface: [[0, 1], [4, 1]]\n", 17, "unit_weight",
                  "water", "give only one of");
  // A surface that does not cross the model (the blocks span x = 0 .. 4).
  expect_error_at(base + "  unit_weight: 9810\n  surface: [[0.5, 1], [4, 1]]\n", 18, "[[0.5", "water.surface",
                  "not the whole model");
  expect_error_at(base + "  unit_weight: 9810\n  surface: [[-1, 1], [3, 1]]\n", 18, "[[-1", "water.surface",
                  "not the whole model");
  expect_error_at(base + "  unit_weight: 9810\n  surface: [[-1, 1], [2, 1], [2, 2], [5, 2]]\n", 18, "[2, 2]",
                  "water.surface[2]", "x must increase strictly");
  expect_error_at(base + "  unit_weight: 9810\n  surface: [[-1, 1]]\n", 18, "[[-1", "water.surface",
                  "expected a list of 2 to");
  // A drawdown table that is not increasing in time.
  expect_error_at(base + "  unit_weight: 9810\n  level_history: [[0, 3], [10, 1], [10, 2]]\n", 18, "[10, 2]",
                  "water.level_history[2]", "times must increase strictly");
  expect_error_at(base + "  unit_weight: 9810\n  level_history: [[0, 3], [10, 1], [5, 2]]\n", 18, "[5, 2]",
                  "water.level_history[2]", "times must increase strictly");
  expect_error_at(base + "  unit_weight: 9810\n  level_history: [[-1, 3]]\n", 18, "[-1", "water.level_history[0]",
                  "time -1 is negative");
  expect_error_at(base + "  unit_weight: 9810\n  level_history: 3\n", 18, "3", "water.level_history",
                  "expected a list of [t, level] samples");
  expect_error_at(base +
                      "  unit_weight: 9810\n  surface_history:\n    - {time: 1, surface: [[-1, 1], [5, 1]]}\n"
                      "    - {time: 1, surface: [[-1, 2], [5, 2]]}\n",
                  20, "1,", "water.surface_history[1].time", "times must increase strictly");
  expect_error_at(base + "  unit_weight: 9810\n  surface_history:\n    - {time: 1, surface: [[1, 1], [5, 1]]}\n", 19,
                  "[[1", "water.surface_history[0].surface", "not the whole model");
  expect_error_at(base + "  unit_weight: 9810\n  surface_history:\n    - {time: 1}\n", 19, "{time",
                  "water.surface_history[0].surface", "missing required key 'surface'");
  expect_error_at(base + "  unit_weight: 9810\n  level: .nan\n", 18, ".nan", "water.level", "not a finite number");
}

BOOST_AUTO_TEST_CASE(a_drained_scene_runs_bit_for_bit_as_the_scene_without_water) {
  // The level below every block: history.csv and the block frames byte for byte
  // those of the scene without `water:`; contacts.csv too, but for its last
  // column water_pressure (all 0).
  auto dry = scene::parse_scene(kBaseScene, "dry.yaml");
  auto drained = scene::parse_scene(kBaseScene + "water: {unit_weight: 9810, level: -5}\n", "drained.yaml");
  for (auto* s : {&dry, &drained}) s->analysis.duration = 0.2, s->analysis.output_interval = 0.05;
  const fs::path a = fresh_dir("water-dry"), b = fresh_dir("water-drained");
  run(dry, a);
  run(drained, b);
  BOOST_TEST(read_text((a / "history.csv").string()) == read_text((b / "history.csv").string()));
  BOOST_TEST(read_text((a / "frames/blocks_000004.vtp").string()) ==
             read_text((b / "frames/blocks_000004.vtp").string()));
  const std::string ca = read_text((a / "contacts.csv").string()), cb = read_text((b / "contacts.csv").string());
  BOOST_TEST(ca.find("water_pressure") == std::string::npos);
  BOOST_TEST(cb.find(",creep_state,water_pressure\n") != std::string::npos);
  BOOST_TEST(ca == without_last_column(cb));
  for (const auto& row : csv_rows(b / "contacts.csv")) BOOST_TEST(row.back() == "0");
  fs::remove_all(a);
  fs::remove_all(b);
}

BOOST_AUTO_TEST_CASE(the_plane_failure_example_slides_when_the_crack_water_reaches_hoek_brays_critical_depth) {
  // examples/water-plane-failure.yaml: z_w(t) = 0.38 t m in the crack; Hoek &
  // Bray's FS = 1 at z_w = 2.6978 m, t = 7.0994 s (water-plane-failure.yaml's
  // comment). Before (up to a step of 0.05 s earlier) the toe moves by the
  // block's elasticity only (micrometres), after it slides. The contacts'
  // water_pressure is gamma_w (h - y) at their points: gamma_w z_w(t) at the
  // foot of the crack (8.66, 5), 0 at the toe.
  const double psi = std::numbers::pi / 6.0, gamma_w = 9810.0, L = 10.0;
  const double W = 2600.0 * 9.81 * 32.908965;
  auto fs_at = [&](double z) {
    const double n = W * std::cos(psi) - 0.5 * gamma_w * z * L - 0.5 * gamma_w * z * z * std::sin(psi);
    const double t = W * std::sin(psi) + 0.5 * gamma_w * z * z * std::cos(psi);
    return n * std::tan(38.0 * std::numbers::pi / 180.0) / t;
  };
  double lo = 0.0, hi = 3.8;
  for (int k = 0; k < 60; ++k) (fs_at(0.5 * (lo + hi)) > 1.0 ? lo : hi) = 0.5 * (lo + hi);
  const double t_c = lo / 0.38;
  BOOST_TEST_MESSAGE("Hoek & Bray: z_w = " << lo << " m at t = " << t_c << " s");

  auto s = scene::load_scene(source_path("examples/water-plane-failure.yaml"));
  s.analysis.history = scene::HistoryRows::steps;  // when the toe passes 0.1 mm: a row per step
  const fs::path out = fresh_dir("water-plane-failure");
  run(s, out);
  std::string header;
  const auto history = csv_rows(out / "history.csv", &header);
  BOOST_TEST_REQUIRE(header.rfind("time,step,dt,cuts,iterations,toe.u,toe.v", 0) == 0u);
  // Past t_c the unbalanced force grows as 7.2e4 N/m x 0.38 m/s x (t - t_c), and
  // a static step of 0.05 s moves the 85 562 kg block by F dt^2 / (2 m): the toe
  // passes 0.1 mm about 0.2 s after t_c.
  double before = 0.0, after = 0.0, first = -1.0;
  for (const auto& r : history) {
    const double t = std::stod(r[0]), d = std::hypot(std::stod(r[5]), std::stod(r[6]));
    if (t < t_c - 0.05) before = std::max(before, d);
    if (d > 1e-4 && first < 0.0) first = t;
    if (t >= 10.0 - 1e-9) after = d;
  }
  BOOST_TEST_MESSAGE("toe: at most " << before << " m before, past 0.1 mm at t = " << first << " s, " << after
                                     << " m at 10 s");
  BOOST_TEST(before < 1e-5);
  BOOST_TEST(first > t_c - 0.05);
  BOOST_TEST(first < t_c + 0.4);
  BOOST_TEST(after > 1e-2);
  // The energy balance closes with the water's work (booked in work_loads).
  const std::size_t residual = header.find("energy_residual_relative") == std::string::npos
                                   ? 0
                                   : std::count(header.begin(), header.begin() + header.find("energy_residual_relative"), ',');
  BOOST_TEST_REQUIRE(residual > 0u);
  BOOST_TEST(std::stod(history.back()[residual]) < 1e-6);

  const auto contacts = csv_rows(out / "contacts.csv", &header);
  BOOST_TEST_REQUIRE(header.substr(header.rfind(',') + 1) == "water_pressure");
  int checked = 0;
  for (const auto& r : contacts) {
    const double t = std::stod(r[0]), x = std::stod(r[10]), y = std::stod(r[11]), p = std::stod(r.back());
    if (t > t_c || r[6] != "block") continue;  // the block's vertices on the plane, while it stands
    if (std::hypot(x - 8.660254038, y - 5.0) < 1e-3) {
      BOOST_TEST(std::abs(p - gamma_w * 0.38 * t) <= 1e-4 * gamma_w * 0.38 * t + 0.1);
      ++checked;
    } else if (std::hypot(x, y) < 1e-3) {
      BOOST_TEST(std::abs(p) <= 1e-3 * gamma_w);
      ++checked;
    }
  }
  BOOST_TEST(checked >= 20);
  fs::remove_all(out);
}

BOOST_AUTO_TEST_CASE(an_interrupted_then_resumed_run_with_water_writes_the_same_files) {
  // The water depends on time only: a run stopped while the crack fills and
  // resumed from its checkpoint writes what the uninterrupted run does.
  auto s = scene::load_scene(source_path("examples/water-plane-failure.yaml"));
  s.analysis.duration = 2.0;
  s.analysis.output_interval = 0.25;
  const fs::path whole = fresh_dir("water-whole"), split = fresh_dir("water-split");
  BOOST_TEST((run(s, whole).status == scene::RunStatus::completed));
  BOOST_TEST((run(s, split, 17).status == scene::RunStatus::interrupted));
  const auto second = run(s, split, -1, true);
  BOOST_TEST((second.status == scene::RunStatus::completed));
  BOOST_TEST(second.resumed_from_step == 17);
  for (const char* f : {"history.csv", "contacts.csv", "frames/contacts_000008.vtp"})
    BOOST_TEST(read_text((split / f).string()) == read_text((whole / f).string()), f);
  BOOST_TEST(read_text((whole / "frames/contacts_000008.vtp").string()).find("Name=\"water_pressure\"") !=
             std::string::npos);
  fs::remove_all(whole);
  fs::remove_all(split);
}

BOOST_AUTO_TEST_SUITE_END()
