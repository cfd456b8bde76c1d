// Values with units in a scene file (docs/reference/scene-format.md, "Units"): each
// dimension converted into the scene's units, a bare number kept as written, a wrong
// dimension refused at file:line:col naming both, a 2D force per unit thickness, `check`
// showing what was given, the gravity warning, and a scene written in SI with units the
// same scene as the one in mm, N, h.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "../scene/run_support.hpp"
#include "rheodda/scene/build.hpp"
#include "rheodda/scene/describe.hpp"

using namespace rheodda;
using namespace rheodda::test;
namespace tt = boost::test_tools;

namespace {

/// The warnings of `text` that hold `part`.
int warnings_with(const std::string& text, const std::string& part) {
  int n = 0;
  for (const auto& w : scene::scene_warnings(scene::parse_scene(text, "w.yaml")))
    if (w.find(part) != std::string::npos) ++n;
  return n;
}

/// examples/shear-creep-test.yaml (mm, N, h) written in SI, every value with its unit.
const std::string kShearCreepSI =
    "title: Shear creep test in SI\n"
    "units: {length: m, force: N, time: s}\n"
    "analysis: {type: static, duration: 200 h, dt: 1 h, output_interval: 2 h, scheme: implicit, gravity: [0, 0]}\n"
    "materials:\n"
    "  rock: {density: 2.08e-16 N*h^2/mm^4, young_modulus: 20000 MPa, poisson_ratio: 0.25}\n"
    "joint_sets:\n"
    "  plane: {friction_angle: 40 deg, record: true,\n"
    "          law: {name: burgers, E1: 26.87 MPa/mm, E2: 192.43 MPa/mm, eta1: 34807.72 MPa*h/mm, eta2: 2141.23 MPa*h/mm}}\n"
    "blocks:\n"
    "  - {name: B, rectangle: {x: 0 mm, y: 0 mm, width: 100 mm, height: 50 mm}, fixed: true}\n"
    "  - {name: A, rectangle: {x: 20 mm, y: 50 mm, width: 60 mm, height: 30 mm}}\n"
    "loads:\n"
    "  - {point: [50 mm, 80 mm], block: A, force: [0, -84.48 N/mm]}\n"
    "  - {point: [20 mm, 65 mm], block: A, force: [13.92 N/mm, 0]}\n"
    "measurement_points:\n"
    "  - {name: A_joint, point: [50 mm, 50 mm], block: A}\n";

/// The last row of `column` in history.csv of `dir`.
double last_value(const std::filesystem::path& dir, const std::string& column) {
  std::ifstream in(dir / "history.csv");
  std::string line, header, last;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (header.empty()) header = line;
    else last = line;
  }
  auto split = [](const std::string& l) {
    std::vector<std::string> f;
    std::stringstream ss(l);
    for (std::string x; std::getline(ss, x, ',');) f.push_back(x);
    return f;
  };
  const auto names = split(header), values = split(last);
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == column) return std::stod(values.at(i));
  BOOST_FAIL("no column " << column);
  return 0.0;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(scene_units)

BOOST_AUTO_TEST_CASE(values_with_units_convert_into_the_scene_units) {
  std::string t = with("duration: 1\n", "duration: 1 min\n");
  t = with("dt: 0.01\n", "dt: 10 ms\n", t);
  t = with("gravity: [0, -9.81]", "gravity: [0, -9.81 m/s^2]", t);
  t = with("density: 2600, young_modulus: 1.0e9", "density: 2.6 t/m^3, young_modulus: 1 GPa", t);
  t = with("bedding: {friction_angle: 30}", "bedding: {friction_angle: 0.5 rad}", t);
  t = with("E1: 1, E2: 2, eta1: 3, eta2: 4", "E1: 1 kPa/km, E2: 2, eta1: 3 Pa*min/m, eta2: 4", t);
  t = with("width: 4, height: 1", "width: 400 cm, height: 1", t);
  const scene::SceneDescription s = scene::parse_scene(t, "u.yaml");
  BOOST_TEST(s.analysis.duration == 60.0);                                  // time
  BOOST_TEST(s.analysis.dt == 0.01, tt::tolerance(1e-15));
  BOOST_TEST(s.analysis.gravity[1] == -9.81);                               // acceleration
  BOOST_TEST(s.materials[0].density == 2600.0, tt::tolerance(1e-15));       // mass/length^3
  BOOST_TEST(s.materials[0].young_modulus == 1e9);                          // stress
  BOOST_TEST(s.joint_sets[0].friction_angle == 0.5 * 180.0 / std::acos(-1.0), tt::tolerance(1e-14));  // angle
  BOOST_TEST(s.joint_sets[1].law->parameters.at("E1") == 1.0, tt::tolerance(1e-15));   // stiffness per area
  BOOST_TEST(s.joint_sets[1].law->parameters.at("eta1") == 180.0, tt::tolerance(1e-15));  // viscosity
  BOOST_TEST(s.joint_sets[1].law->parameters.at("E2") == 2.0);               // bare: as written
  BOOST_TEST(s.blocks[0].polygon[1][0] == 4.0, tt::tolerance(1e-15));       // length
  BOOST_TEST(s.given_quantities.size() == 9u);
  BOOST_TEST(s.given_quantities[0].key == "analysis.duration");
  BOOST_TEST(s.given_quantities[0].text == "1 min");
  BOOST_TEST(s.given_quantities[0].where.line == 3);
  // check says each in the scene's units with the text it was given as
  const std::string d = scene::describe_scene(s);
  BOOST_TEST_INFO(d);
  BOOST_TEST(d.find("analysis.duration 60 s (given as 1 min at line 3)") != std::string::npos);
  BOOST_TEST(d.find("materials.rock.density 2600 ") != std::string::npos);
  BOOST_TEST(d.find("(given as 2.6 t/m^3 at line 7)") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(force_and_spring_stiffness_convert) {
  const std::string t = kBaseScene + "loads:\n  - {point: [1.5, 1.5], block: top, force: [2 kN/m, -3 kN]}\n";
  const scene::SceneDescription s = scene::parse_scene(t, "f.yaml");
  BOOST_TEST(s.loads[0].history[0][1] == 2000.0);  // per metre of thickness: as given
  BOOST_TEST(s.loads[0].history[0][2] == -3000.0);  // a bare force: per unit thickness of the scene's length
  BOOST_TEST(!s.given_quantities[0].per_thickness);
  BOOST_TEST(s.given_quantities[1].per_thickness);
  const std::string d = scene::describe_scene(s);
  BOOST_TEST_INFO(d);
  BOOST_TEST(d.find("read as per m of thickness, write -3 kN/m to say so") != std::string::npos);
  // in a scene in mm the same load per metre is 1/1000 of it per mm
  const std::string mm = with("units: {length: m, force: N, time: s}", "units: {length: mm, force: N, time: s}", t);
  BOOST_TEST(scene::parse_scene(mm, "f.yaml").loads[0].history[0][1] == 2.0, tt::tolerance(1e-15));
  const auto k = scene::parse_scene(with("gravity: [0, -9.81]", "gravity: [0, -9.81]\n  fixed_point_stiffness: 2 kN/mm"),
                                    "k.yaml");
  BOOST_TEST(k.analysis.fixed_point_stiffness == 2e6, tt::tolerance(1e-15));  // force/length
}

BOOST_AUTO_TEST_CASE(each_item_of_a_sample_has_its_own_dimension) {
  // A load history's [t, fx, fy]: a time, then two forces.
  const std::string t =
      kBaseScene + "loads:\n  - {point: [1.5, 1.5], block: top, history: [[0, 0, 0], [0.5 min, 1 kN/m, -2 kN/m]]}\n";
  const scene::SceneDescription s = scene::parse_scene(t, "h.yaml");
  BOOST_TEST_REQUIRE(s.loads[0].history.size() == 2u);
  BOOST_TEST(s.loads[0].history[1][0] == 30.0);
  BOOST_TEST(s.loads[0].history[1][1] == 1000.0);
  BOOST_TEST(s.loads[0].history[1][2] == -2000.0);
  expect_error_at(with("[0.5 min, 1 kN/m", "[0.5 m, 1 kN/m", t), 17, "0.5 m", "loads[0].history[1][0]",
                  "m is length, this key takes time");
}

BOOST_AUTO_TEST_CASE(a_bare_number_is_kept_exactly) {
  const scene::SceneDescription a = scene::parse_scene(kBaseScene, "a.yaml");
  BOOST_TEST(a.given_quantities.empty());
  BOOST_TEST(a.analysis.dt == 0.01);
  BOOST_TEST(scene::describe_scene(a).find("given with a unit") == std::string::npos);
}

BOOST_AUTO_TEST_CASE(a_wrong_dimension_is_refused_at_the_value_naming_both) {
  const std::string t = with("density: 2600", "density: 2600 kg/m^2");
  expect_error_at(t, 7, "2600 kg", "materials.rock.density",
                  "kg/m^2 is force*time^2/length^3, this key takes mass/length^3 = force*time^2/length^4");
  expect_error_at(with("duration: 1\n", "duration: 1 m\n"), 3, "1 m", "analysis.duration",
                  "m is length, this key takes time (s in this scene's units)");
  expect_error_at(with("eta1: 3", "eta1: 3 MPa*h"), 10, "3 MPa", "joint_sets.fault.law.eta1",
                  "this key takes stress*time/length = force*time/length^3");
  expect_error_at(with("gravity: [0, -9.81]", "gravity: [0, -9.81 m/s]"), 5, "-9.81 m/s", "analysis.gravity[1]",
                  "m/s is length/time, this key takes length/time^2");
  expect_error_at(with("poisson_ratio: 0.25", "poisson_ratio: 0.25 m"), 7, "0.25 m", "poisson_ratio",
                  "m is length, this key is dimensionless");
  expect_error_at(with("young_modulus: 1.0e9", "young_modulus: 1 GPx"), 7, "1 GPx", "young_modulus",
                  "unknown unit 'GPx'");
}

BOOST_AUTO_TEST_CASE(scene_labels_udunits_does_not_know_take_bare_numbers_only) {
  const std::string odd = with("units: {length: m, force: N, time: s}", "units: {length: m, force: N, time: tick}");
  BOOST_TEST(scene::parse_scene(odd, "odd.yaml").analysis.dt == 0.01);
  expect_error_at(with("duration: 1\n", "duration: 1 s\n", odd), 3, "1 s", "analysis.duration",
                  "not all units UDUNITS-2 knows");
}

BOOST_AUTO_TEST_CASE(gravity_that_is_not_the_earths_in_the_scene_units_is_a_warning) {
  BOOST_TEST(warnings_with(kBaseScene, "gravity") == 0);
  const std::string days = with("units: {length: m, force: N, time: s}", "units: {length: m, force: N, time: d}");
  BOOST_TEST(warnings_with(days, "9.81 m/s^2 is 7.32313e+10 m/d^2") == 1);  // the user's `gravity: [0, -9.81]` in days
  BOOST_TEST(warnings_with(with("gravity: [0, -9.81]", "gravity: [0, -9.81 m/s^2]", days), "gravity") == 0);
  BOOST_TEST(warnings_with(with("gravity: [0, -9.81]", "gravity: [0, -7.32313e10]", days), "gravity") == 0);
  BOOST_TEST(warnings_with(with("gravity: [0, -9.81]", "gravity: [0, -9.5]"), "gravity") == 1);   // 3 % off
  BOOST_TEST(warnings_with(with("gravity: [0, -9.81]", "gravity: [0, -9.7]"), "gravity") == 0);   // 1 % off
  BOOST_TEST(warnings_with(with("gravity: [0, -9.81]", "gravity: [0, 0]"), "gravity") == 0);      // none: deliberate
  BOOST_TEST(warnings_with(with("gravity: [0, -9.81]", "gravity: [0, -1.62]\n  accept_other_gravity: true"),
                           "gravity") == 0);  // the Moon, said so
  const std::string mm = with("units: {length: m, force: N, time: s}", "units: {length: mm, force: N, time: h}");
  BOOST_TEST(warnings_with(mm, "9.81 m/s^2 is 1.27138e+11 mm/h^2") == 1);
}

BOOST_AUTO_TEST_CASE(a_scene_in_si_with_units_is_the_same_scene_as_in_mm_n_h) {
  scene::SceneDescription mm = scene::load_scene(source_path("examples/shear-creep-test.yaml"));
  scene::SceneDescription si = scene::parse_scene(kShearCreepSI, "si.yaml");
  const double h = 3600.0, mpa = 1e6, per_mm = 1e3;
  BOOST_TEST(si.analysis.duration == mm.analysis.duration * h);
  BOOST_TEST(si.analysis.dt == mm.analysis.dt * h);
  BOOST_TEST(si.materials[0].young_modulus == mm.materials[0].young_modulus * mpa, tt::tolerance(1e-14));
  BOOST_TEST(si.materials[0].density == mm.materials[0].density * 1e3 * h * h * 1e9, tt::tolerance(1e-14));  // N*s^2/m^4
  for (const char* p : {"E1", "E2"})
    BOOST_TEST(si.joint_sets[0].law->parameters.at(p) == mm.joint_sets[0].law->parameters.at(p) * mpa * per_mm,
               tt::tolerance(1e-14));
  for (const char* p : {"eta1", "eta2"})
    BOOST_TEST(si.joint_sets[0].law->parameters.at(p) == mm.joint_sets[0].law->parameters.at(p) * mpa * h * per_mm,
               tt::tolerance(1e-14));
  BOOST_TEST(si.loads[0].history[0][2] == mm.loads[0].history[0][2] * per_mm, tt::tolerance(1e-14));  // N per m of thickness
  BOOST_TEST(si.blocks[1].polygon[2][0] == mm.blocks[1].polygon[2][0] / per_mm, tt::tolerance(1e-14));
  // Both run (the first 20 h): the same creep, in their own units.
  mm.analysis.duration = 20.0;
  si.analysis.duration = 20.0 * h;
  si.file = mm.file;  // the checkpoint hashes the file's text: any text will do
  const auto dir = std::filesystem::temp_directory_path() / "rheodda-units-test";
  std::filesystem::remove_all(dir);
  run(mm, dir / "mm");
  run(si, dir / "si");
  for (const char* c : {"plane.shear_displacement", "A_joint.u", "A_joint.v"})
    BOOST_TEST(last_value(dir / "si", c) == last_value(dir / "mm", c) / per_mm, tt::tolerance(1e-6));
  BOOST_TEST(last_value(dir / "si", "time") == 20.0 * h, tt::tolerance(1e-12));
  std::filesystem::remove_all(dir);
}

BOOST_AUTO_TEST_CASE(the_shipped_examples_are_read_as_before) {
  // Bare numbers throughout, the Earth's gravity (or none) in each one's units: nothing given
  // with a unit, no gravity warning; their results are pinned by tests/python/test_example_results.py.
  int scenes = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(source_path("examples"))) {
    if (e.path().extension() != ".yaml") continue;
    const std::string text = read_text(e.path().string());
    if (text.find("\nunits:") == std::string::npos) continue;  // a study file
    const scene::SceneDescription s = scene::load_scene(e.path().string());
    BOOST_TEST(s.given_quantities.empty(), e.path());
    for (const auto& w : scene::scene_warnings(s)) BOOST_TEST(w.find("gravity") == std::string::npos, e.path() << ": " << w);
    ++scenes;
  }
  BOOST_TEST(scenes >= 15);
}

BOOST_AUTO_TEST_CASE(the_command_line_reads_times_with_their_units) {
  const std::string slope = source_path("examples/goodman-toppling.yaml");  // m, N, d
  CommandResult r = run_rheodda("check " + slope + " --refine=2 --until '2 m' -o /tmp/rheodda-units-never");
  BOOST_TEST(r.exit_code == 2, r.output);
  BOOST_TEST(r.output.find("--until: '2 m' has the wrong dimension: m is length, this key takes time") !=
             std::string::npos, r.output);
  BOOST_TEST(!std::filesystem::exists("/tmp/rheodda-units-never"));
  // check of the user's scene: gravity 9.81 in a scene whose time is days, values with units listed
  const auto dir = std::filesystem::temp_directory_path() / "rheodda-units-check";
  std::filesystem::create_directories(dir);
  const std::string days = with("units: {length: m, force: N, time: s}", "units: {length: m, force: N, time: d}",
                                with("duration: 1\n", "duration: 100 d\n"));
  std::ofstream(dir / "days.yaml") << days;
  r = run_rheodda("check " + (dir / "days.yaml").string());
  BOOST_TEST(r.exit_code == 0, r.output);
  BOOST_TEST(r.output.find("analysis.duration 100 d (given as 100 d at line 3)") != std::string::npos, r.output);
  BOOST_TEST(r.output.find("9.81 m/s^2 is 7.32313e+10 m/d^2 in the scene's units") != std::string::npos, r.output);
  std::filesystem::remove_all(dir);
}

BOOST_AUTO_TEST_SUITE_END()
