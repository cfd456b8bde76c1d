// Bolts in scene files (docs/reference/bolts.md, docs/reference/scene-format.md "bolts"): the loader
// reads them and refuses bad ones with file:line:col and the key; scenes with
// contacts against closed forms (a block on an incline steeper than its
// friction angle held by a bolt, examples/bolted-block.yaml; a pretensioned
// bolt raising a joint's normal force and the friction it holds); a run writes
// bolts.csv and the bolt frames, and refuses --resume.
#include <boost/test/unit_test.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "run_support.hpp"
#include "rheodda/scene/assemble.hpp"
#include "rheodda/scene/build.hpp"
#include "rheodda/scene/describe.hpp"
#include "rheodda/scene/loader.hpp"
#include "rheodda/scene/plot.hpp"

using namespace rheodda;
using namespace rheodda::test;
namespace fs = std::filesystem;

namespace {

/// kBaseScene with one bolt (line 17) from the top block to an anchor above it.
const std::string kBoltScene =
    kBaseScene +
    "bolts:\n"                                                                                          // 16
    "  - {name: b1, from: {point: [1.5, 2], block: top}, to: {fixed: [1.5, 4]}, axial_stiffness: 1.0e6}\n";  // 17

std::string bolt_with(const std::string& from, const std::string& to) { return with(from, to, kBoltScene); }

/// The scene's engine run to its duration.
struct Ran {
  scene::SceneDescription s;
  scene::BuiltScene built;
  scene::AssembledScene as;
  explicit Ran(const std::string& text) : s(scene::parse_scene(text, "bolts.yaml")), built(scene::build_scene(s)) {
    as = scene::assemble_scene(s, built);
    as.engine->run_until(s.analysis.duration);
  }
};

/// A 1 m block on a fixed base (friction 30 deg), pushed sideways by F = 1.5 W tan 30,
/// more than friction holds (W tan 30); with `bolt`, a vertical bolt through the joint
/// into the base pretensioned to P = W, so that (W + P) tan 30 holds it.
std::string pushed_block(bool bolt) {
  const double W = 2600.0 * 9.81;  // N per m of thickness
  std::string text =
      "units: {length: m, force: N, time: s}\n"
      "analysis: {type: static, duration: 0.5, dt: 0.01, gravity: [0, -9.81]}\n"
      "materials:\n"
      "  rock: {density: 2600, young_modulus: 5.0e10, poisson_ratio: 0.25}\n"
      "joint_sets:\n"
      "  joint: {friction_angle: 30}\n"
      "blocks:\n"
      "  - {name: base, rectangle: {x: 0, y: 0, width: 4, height: 1}, fixed: true}\n"
      "  - {name: top, rectangle: {x: 1, y: 1, width: 1, height: 1}}\n" +
      fmt::format("loads:\n  - {{point: [1, 1.5], block: top, force: [{:.17g}, 0]}}\n",
                  1.5 * W * std::tan(std::numbers::pi / 6.0));
  if (bolt)
    text += fmt::format(
        "bolts:\n  - {{name: tie, from: {{point: [1.5, 1.8], block: top}}, to: {{point: [1.5, 0.2], block: base}}, "
        "axial_stiffness: 1.0e7, pretension: {:.17g}}}\n",
        W);
  return text;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(scene_bolts)

BOOST_AUTO_TEST_CASE(bolts_load_with_their_defaults) {
  const auto s = scene::parse_scene(kBoltScene, "bolts.yaml");
  BOOST_TEST_REQUIRE(s.bolts.size() == 1u);
  const auto& b = s.bolts[0];
  BOOST_TEST(b.name == "b1");
  BOOST_TEST(b.from.block == 1);
  BOOST_TEST(b.to_fixed);
  BOOST_TEST(b.to.block == -1);
  BOOST_TEST(b.axial_stiffness == 1.0e6);
  BOOST_TEST(b.pretension == 0.0);
  BOOST_TEST(std::isinf(b.yield_force));  // never yields
  BOOST_TEST(std::isinf(b.rupture_elongation));  // never ruptures
  BOOST_TEST(!b.law.has_value());
  // A law's E1 is the spring when axial_stiffness is left out.
  const auto t = scene::parse_scene(
      bolt_with("axial_stiffness: 1.0e6}", "law: {name: burgers, E1: 5, E2: 2, eta1: 3, eta2: 4}}"), "law.yaml");
  BOOST_TEST(t.bolts[0].axial_stiffness == 5.0);
  BOOST_TEST(t.bolts[0].law->name == "burgers");
  // `rheodda check` lists it.
  BOOST_TEST(scene::describe_scene(s).find("bolts: 1\n  b1: (1.5, 2) on top to fixed at (1.5, 4)") != std::string::npos);
  // The built model has it: block-to-block as well as to a fixed anchor.
  const auto m = scene::build_scene(scene::parse_scene(
      bolt_with("to: {fixed: [1.5, 4]}", "to: {point: [2, 0.5], block: base}"), "two.yaml"));
  BOOST_TEST(m.model.bolts.at(0).block_a == 1);
  BOOST_TEST(m.model.bolts.at(0).block_b == 0);
}

BOOST_AUTO_TEST_CASE(bad_bolts_are_refused_at_their_line_and_column) {
  // An end off its block.
  expect_error_at(bolt_with("point: [1.5, 2], block: top", "point: [3, 3], block: top"), 17, "[3, 3]",
                  "bolts[0].from.point", "is not on block 'top'");
  // Both ends on one block.
  expect_error(bolt_with("to: {fixed: [1.5, 4]}", "to: {point: [1.2, 1.2], block: top}"), 17, 0, "bolts[0].to",
               "both ends are on block 'top'");
  // Negative or zero stiffness.
  expect_error_at(bolt_with("axial_stiffness: 1.0e6", "axial_stiffness: -5"), 17, "-5", "bolts[0].axial_stiffness",
                  "out of range");
  // An unknown key, with a hint.
  expect_error_at(bolt_with("axial_stiffness: 1.0e6", "axial_stiffnes: 1.0e6"), 17, "axial_stiffnes",
                  "bolts[0].axial_stiffnes", "did you mean 'axial_stiffness'");
  expect_error_at(bolt_with("to: {fixed: [1.5, 4]}", "to: {fixed: [1.5, 4], pont: [1, 1]}"), 17, "pont",
                  "bolts[0].to.pont", "unknown key 'pont'");
  // Missing stiffness (and no law's E1), missing end.
  expect_error(bolt_with(", axial_stiffness: 1.0e6}", "}"), 17, 0, "bolts[0].axial_stiffness", "missing required key");
  expect_error(bolt_with("to: {fixed: [1.5, 4]}, ", ""), 17, 0, "bolts[0].to", "missing required key 'to'");
  // An anchor both fixed and on a block.
  expect_error(bolt_with("to: {fixed: [1.5, 4]}", "to: {fixed: [1.5, 4], point: [2, 0.5]}"), 17, 0,
               "bolts[0].to.fixed", "either");
  // The ends at one point.
  expect_error(bolt_with("to: {fixed: [1.5, 4]}", "to: {fixed: [1.5, 2]}"), 17, 0, "bolts[0].to", "coincide");
  // Pretension beyond the yield force, or stretching it beyond its rupture elongation.
  expect_error_at(bolt_with("axial_stiffness: 1.0e6}", "axial_stiffness: 1.0e6, yield_force: 10, pretension: 20}"),
                  17, "20", "bolts[0].pretension", "exceeds the yield force");
  expect_error_at(
      bolt_with("axial_stiffness: 1.0e6}", "axial_stiffness: 1.0e6, rupture_elongation: 1.0e-3, pretension: 2.0e3}"),
      17, "2.0e3", "bolts[0].pretension", "rupture_elongation");
  expect_error_at(bolt_with("axial_stiffness: 1.0e6}", "axial_stiffness: 1.0e6, yield_force: 0}"), 17, "0}",
                  "bolts[0].yield_force", "out of range");
  // A law whose E1 is another spring than axial_stiffness.
  expect_error_at(bolt_with("axial_stiffness: 1.0e6}", "axial_stiffness: 1.0e6, law: {name: maxwell, E1: 5, eta1: 3}}"),
                  17, "1.0e6", "bolts[0].axial_stiffness", "E1");
  // A law unknown.
  expect_error(bolt_with("axial_stiffness: 1.0e6}", "axial_stiffness: 1.0e6, law: {name: burger}}"), 17, 0,
               "bolts[0].law.name", "unknown law");
  // Two bolts of one name; `bolts:` not a list.
  expect_error(kBoltScene + "  - {name: b1, from: {point: [1.5, 2]}, to: {fixed: [2, 4]}, axial_stiffness: 1}\n", 18, 0,
               "bolts[1].name", "defined twice");
  expect_error(kBaseScene + "bolts: {a: 1}\n", 16, 0, "bolts", "expected a list");
}

BOOST_AUTO_TEST_CASE(bolt_holds_a_block_on_an_incline_steeper_than_its_friction_angle) {
  // examples/bolted-block.yaml: 30 deg slope, friction 20 deg, the bolt along the
  // slope. At rest the bolt carries what friction cannot:
  //   N = W (sin 30 - cos 30 tan 20),  W = rho g A = 2600 x 9.81 x 0.5 N/m.
  const Ran r(read_text(source_path("examples/bolted-block.yaml")));
  const double a = std::numbers::pi / 6.0, phi = 20.0 * std::numbers::pi / 180.0;
  const double W = 2600.0 * 9.81 * 0.5;
  const double N = W * (std::sin(a) - std::cos(a) * std::tan(phi));
  const core::BoltState& b = r.as.engine->bolts().at(0);
  BOOST_TEST_MESSAGE("bolted block: bolt force " << b.force << " N, closed form " << N << " N, relative error "
                                                 << (b.force - N) / N);
  BOOST_TEST((b.state == core::BoltMode::elastic));
  BOOST_TEST(std::abs(b.force - N) <= 1e-3 * N);
  BOOST_TEST(std::abs(b.elongation - b.force / 1.0e7) <= 1e-9 * b.force / 1.0e7);
  // The block stands: the displacement of its centre over the last half of the run
  // is a round-off of the bolt's stretch.
  BOOST_TEST(r.as.engine->point_displacement(1, {5.504165125, 3.466506351}).norm() < 2.0 * N / 1.0e7 + 1e-4);
}

BOOST_AUTO_TEST_CASE(pretensioned_bolt_raises_the_joint_normal_force_and_the_friction_it_holds) {
  const double W = 2600.0 * 9.81, F = 1.5 * W * std::tan(std::numbers::pi / 6.0);
  // Without the bolt, F > W tan 30 and the block slides.
  {
    const Ran r(pushed_block(false));
    BOOST_TEST(r.as.engine->point_displacement(1, {1.5, 1.5}).x() > 3e-3);
  }
  // With it, the joint's normal force is W + N_bolt (vertical equilibrium, the bolt
  // vertical) and (W + P) tan 30 > F holds it. N_bolt is P less k times the shortening
  // between the bolt's ends (the block's elastic strain and the joint's penetration
  // under W + P: about 4e-7 m with E = 5e10 Pa, 2e-4 of P).
  const Ran r(pushed_block(true));
  const core::BoltState& b = r.as.engine->bolts().at(0);
  double normal = 0.0, shear = 0.0;
  for (const auto& c : r.as.contacts->contacts())
    if (c.state != contact::ContactState::open) normal += c.normal_force, shear += c.shear_force;
  BOOST_TEST_MESSAGE("pretensioned bolt: force " << b.force << " N (P = " << W << "), joint normal force " << normal
                                                 << " N, shear " << shear << " N (F = " << F << ")");
  BOOST_TEST(std::abs(b.force - W) <= 1e-3 * W);
  BOOST_TEST(std::abs(normal - (W + b.force)) <= 1e-4 * W);
  BOOST_TEST(std::abs(std::abs(shear) - F) <= 1e-4 * F);
  BOOST_TEST(std::abs(r.as.engine->point_displacement(1, {1.5, 1.5}).x()) < 1e-4);
}

BOOST_AUTO_TEST_CASE(a_run_writes_bolts_csv_and_bolt_frames_and_refuses_resume) {
  auto s = scene::load_scene(source_path("examples/bolted-block.yaml"));
  s.analysis.duration = 0.2;
  const fs::path out = fresh_dir("bolts-run");
  (void)run(s, out);
  const std::string csv = read_text((out / "bolts.csv").string());
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  BOOST_TEST(line.rfind("# units: length=m force=N time=s", 0) == 0u);
  std::getline(in, line);
  BOOST_TEST(line == "time,step,bolt,state,force,elongation,plastic_elongation,creep_elongation,length,rupture_time");
  int rows = 0;
  while (std::getline(in, line)) {
    ++rows;
    BOOST_TEST(line.find(",anchor,elastic,") != std::string::npos);
  }
  BOOST_TEST(rows == 3);  // t = 0, 0.1, 0.2
  // history.csv ends with the bolts' energy columns, and its balance closes with them.
  {
    std::istringstream h(read_text((out / "history.csv").string()));
    std::string l, last;
    std::getline(h, l);
    std::getline(h, l);
    const std::string tail = ",energy_bolt,dissipation_bolt";
    BOOST_TEST_REQUIRE(l.size() > tail.size());
    BOOST_TEST(l.substr(l.size() - tail.size()) == tail);
    while (std::getline(h, l)) last = l;
    BOOST_TEST(std::stod(last.substr(last.rfind(',', last.rfind(',') - 1) + 1)) > 0.0);  // energy_bolt
  }
  BOOST_TEST(fs::exists(out / "bolts.pvd"));
  BOOST_TEST(fs::exists(out / "frames/bolts_000002.vtp"));
  BOOST_TEST(read_text((out / "frames/bolts_000002.vtp").string()).find("NumberOfLines=\"1\"") != std::string::npos);
  // `rheodda plot` draws the bolt forces.
  scene::PlotOptions po;
  po.out_dir = out.string();
  const auto pictures = scene::plot_run(po);
  BOOST_TEST((std::find(pictures.begin(), pictures.end(), (out / "plots" / "bolts.png").string()) != pictures.end()));
  BOOST_TEST(fs::file_size(out / "plots" / "bolts.png") > 0u);
  // --resume: refused, the outputs untouched.
  BOOST_CHECK_THROW((void)run(s, out, -1, true), std::invalid_argument);
  BOOST_TEST(read_text((out / "bolts.csv").string()) == csv);
  // A scene without bolts writes none of it.
  const fs::path plain = fresh_dir("bolts-none");
  (void)run(sliding(0.01, 0.01), plain);
  BOOST_TEST(!fs::exists(plain / "bolts.csv"));
  BOOST_TEST(!fs::exists(plain / "bolts.pvd"));
}

BOOST_AUTO_TEST_SUITE_END()
