// `rheodda check SCENE --refine`: the refinement study halves every step control
// the scene uses, level by level, and its verdict follows the levels' results:
// fine when L0 is within the tolerance of the (extrapolated) finest level and the
// levels converge, coarse (with the first level that is fine) when they converge
// away from L0, not converged, or incomplete. End to end on a shear creep test
// with its shear load ramped (the implicit scheme is first order under a ramp):
// dt 50 h is coarse, dt 10 h fine, compared with a closed-form check of the
// extrapolated limit.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <string>

#include "rheodda/study/refinement.hpp"
#include "study_support.hpp"

using namespace rheodda::study_test;
namespace fs = std::filesystem;
namespace st = rheodda::study;

namespace {

/// The Override of a case with key `key`, or nullptr.
const st::Override* find(const st::StudyCase& c, const std::string& key) {
  for (const auto& o : c.set)
    if (o.key == key) return &o;
  return nullptr;
}

/// A refinement of `levels` levels, one output at one time, with these values per level.
st::RefinementStudy synthetic(std::size_t levels, std::size_t outputs) {
  st::RefinementStudy r;
  for (std::size_t i = 0; i < outputs; ++i) r.study.outputs.push_back("p" + std::to_string(i) + ".displacement");
  r.study.times = {1.0};
  for (std::size_t k = 0; k < levels; ++k) {
    r.study.cases.push_back({});
    r.study.cases.back().name = "L" + std::to_string(k);
    r.level_controls.push_back("dt " + std::to_string(1.0 / double(1 << k)));
  }
  return r;
}

std::vector<st::CaseResult> results(const std::vector<std::vector<double>>& per_output) {
  std::vector<st::CaseResult> out(per_output.front().size());
  for (std::size_t k = 0; k < out.size(); ++k) {
    out[k].name = "L" + std::to_string(k);
    out[k].status = "completed";
    for (const auto& v : per_output) out[k].values.push_back(v[k]);
  }
  return out;
}

/// The shear creep test of the seed's Table 1 row 1 with its shear load ramped from
/// 0 to 13.92 N over the 200 h, at time step `dt` [h].
fs::path ramped_creep_test(const fs::path& dir, const std::string& dt) {
  const fs::path p = dir / ("ramp-dt" + dt + ".yaml");
  std::string t = read_text(source_path("examples/shear-creep-test.yaml"));
  t = with("  dt: 1  ", "  dt: " + dt + "  ", t);
  t = with("  output_interval: 2  ", "  output_interval: 50  ", t);
  t = with("force: [13.92, 0]}", "history: [[0, 0, 0], [200, 13.92, 0]]}", t);
  std::ofstream(p) << t;
  return p;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(refinement)

BOOST_AUTO_TEST_CASE(every_step_control_the_scene_uses_is_halved_level_by_level) {
  const fs::path dir = fresh_dir("refine-study");
  st::RefinementOptions o;
  o.levels = 3;
  const auto r = st::refinement_study(source_path("examples/goodman-toppling-creep.yaml"),
                                      (dir / "refinement.yaml").string(), o);
  BOOST_TEST_REQUIRE(r.study.cases.size() == 3u);
  BOOST_TEST(r.study.cases[0].set.empty());  // L0 is the scene as written
  const auto& l2 = r.study.cases[2];
  // The example: dt 1/32 d, max_displacement_ratio 0.01 (default), settle {until 0.01, dt 5e-5, max_displacement_ratio 2.5e-4}.
  BOOST_TEST_REQUIRE(find(l2, "analysis.dt") != nullptr);
  BOOST_TEST(std::stod(find(l2, "analysis.dt")->value_yaml) == 0.0078125);
  BOOST_TEST(std::stod(find(l2, "analysis.max_displacement_ratio")->value_yaml) == 0.0025);
  BOOST_TEST(std::stod(find(l2, "analysis.settle.dt")->value_yaml) == 1.25e-5);
  BOOST_TEST(std::stod(find(l2, "analysis.settle.max_displacement_ratio")->value_yaml) == 6.25e-5);
  BOOST_TEST(find(l2, "analysis.step_tolerance") == nullptr);  // not used by the scene: not touched
  // Outputs: both measurement points, both recorded joint sets, the work of gravity; half-way and the end.
  BOOST_TEST(r.study.outputs == (std::vector<std::string>{"block1_top.displacement", "block10_top.displacement",
                                                          "base.shear_displacement_magnitude",
                                                          "anti_toppling.shear_displacement_magnitude",
                                                          "work_gravity"}),
             boost::test_tools::per_element());
  BOOST_TEST(r.study.times == (std::vector<double>{50.0, 100.0}), boost::test_tools::per_element());
  // The study as a file reads back as the same study, and every level is a valid scene.
  std::ofstream(dir / "refinement.yaml") << r.study_text;
  const st::StudyDescription back = st::load_study((dir / "refinement.yaml").string());
  BOOST_TEST_REQUIRE(back.cases.size() == 3u);
  BOOST_TEST(std::stod(find(back.cases[2], "analysis.settle.dt")->value_yaml) == 1.25e-5);
  BOOST_TEST(st::prepare_cases(r.study).size() == 3u);
}

BOOST_AUTO_TEST_CASE(the_explicit_steps_cycle_is_refined_with_the_other_step_controls) {
  // docs/reference/explicit-step.md: under integrator: explicit, explicit_safety is a step
  // control, halved level by level with dt and max_displacement_ratio; the study reads back as the same levels.
  const fs::path dir = fresh_dir("refine-explicit");
  std::string t = read_text(source_path("examples/sliding-block.yaml"));
  t = with("  type: dynamic\n", "  type: dynamic\n  integrator: explicit\n", t);
  const fs::path scene = dir / "sliding-explicit.yaml";
  std::ofstream(scene) << t;
  st::RefinementOptions o;
  o.levels = 3;
  const auto r = st::refinement_study(scene.string(), (dir / "r.yaml").string(), o);
  BOOST_TEST_REQUIRE(r.study.cases.size() == 3u);
  BOOST_TEST_REQUIRE(find(r.study.cases[2], "analysis.explicit_safety") != nullptr);
  BOOST_TEST(std::stod(find(r.study.cases[2], "analysis.explicit_safety")->value_yaml) == 0.2);
  BOOST_TEST(r.level_controls[1].find("explicit_safety 0.4") != std::string::npos, r.level_controls[1]);
  std::ofstream(dir / "r.yaml") << r.study_text;
  const st::StudyDescription back = st::load_study((dir / "r.yaml").string());
  BOOST_TEST_REQUIRE(back.cases.size() == 3u);
  BOOST_TEST(std::stod(find(back.cases[2], "analysis.explicit_safety")->value_yaml) == 0.2);
  BOOST_TEST(st::prepare_cases(r.study).size() == 3u);
}

BOOST_AUTO_TEST_CASE(density_scaled_stages_refine_with_twice_the_cycles) {
  // docs/reference/explicit-step.md, "Density scaling": halving the stages' dt and
  // explicit_safety at a fixed stage_cycles would keep their cycle and scale more mass; the
  // refinement doubles stage_cycles instead, level by level.
  const fs::path dir = fresh_dir("refine-density");
  std::string t = read_text(source_path("bench/scenes/jointed-slope-cohesionless.yaml"));
  t = with("  type: static\n", "  type: static\n  integrator: explicit\n  stage_cycles: 50\n", t);
  t = with("settle: {type: dynamic,", "settle: {type: dynamic, until: 0.001,", t);  // a stage shorter than the run
  const fs::path scene = dir / "slope-scaled.yaml";
  std::ofstream(scene) << t;
  st::RefinementOptions o;
  o.levels = 3;
  const auto r = st::refinement_study(scene.string(), (dir / "r.yaml").string(), o);
  BOOST_TEST_REQUIRE(r.study.cases.size() == 3u);
  BOOST_TEST_REQUIRE(find(r.study.cases[2], "analysis.stage_cycles") != nullptr);
  BOOST_TEST(find(r.study.cases[2], "analysis.stage_cycles")->value_yaml == "200");
  BOOST_TEST(std::stod(find(r.study.cases[2], "analysis.explicit_safety")->value_yaml) == 0.2);
  BOOST_TEST(r.level_controls[1].find("stage_cycles 100") != std::string::npos, r.level_controls[1]);
  std::ofstream(dir / "r.yaml") << r.study_text;
  BOOST_TEST(st::load_study((dir / "r.yaml").string()).cases.size() == 3u);
}

BOOST_AUTO_TEST_CASE(held_step_controls_keep_the_scene_value_and_the_others_are_halved) {
  const fs::path dir = fresh_dir("refine-hold");
  const std::string scene = source_path("examples/goodman-toppling-creep.yaml");
  const std::string file = (dir / "r.yaml").string();
  st::RefinementOptions o;
  o.levels = 3;
  o.hold = {"settle.dt", "settle.max_displacement_ratio"};
  const auto r = st::refinement_study(scene, file, o);
  BOOST_TEST_REQUIRE(r.study.cases.size() == 3u);
  const auto& l2 = r.study.cases[2];
  BOOST_TEST(find(l2, "analysis.settle.dt") == nullptr);  // held: the scene's 5e-5 d on every level
  BOOST_TEST(find(l2, "analysis.settle.max_displacement_ratio") == nullptr);
  BOOST_TEST_REQUIRE(find(l2, "analysis.dt") != nullptr);  // the others halved as before
  BOOST_TEST(std::stod(find(l2, "analysis.dt")->value_yaml) == 0.0078125);
  BOOST_TEST(std::stod(find(l2, "analysis.max_displacement_ratio")->value_yaml) == 0.0025);
  BOOST_TEST(r.level_controls[2].find("settle dt 5e-05 d (held)") != std::string::npos, r.level_controls[2]);
  // The study file reruns the same levels.
  std::ofstream(file) << r.study_text;
  const st::StudyDescription back = st::load_study(file);
  BOOST_TEST_REQUIRE(back.cases.size() == 3u);
  BOOST_TEST(find(back.cases[2], "analysis.settle.dt") == nullptr);
  // A key that is not one of the scene's step controls is refused, naming them.
  o.hold = {"settle.dt", "step_tolerance"};
  try {
    st::refinement_study(scene, file, o);
    BOOST_FAIL("--hold step_tolerance was accepted");
  } catch (const std::invalid_argument& e) {
    const std::string m = e.what();
    BOOST_TEST(m.find("--hold step_tolerance: not a step control") != std::string::npos, m);
    BOOST_TEST(m.find("dt, max_displacement_ratio, settle.dt, settle.max_displacement_ratio") != std::string::npos, m);
  }
  // Holding every control leaves nothing to refine.
  o.hold = {"dt", "max_displacement_ratio", "settle.dt", "settle.max_displacement_ratio"};
  BOOST_CHECK_THROW(st::refinement_study(scene, file, o), std::invalid_argument);
}

BOOST_AUTO_TEST_CASE(until_shortens_every_level_and_options_out_of_range_are_refused) {
  const fs::path dir = fresh_dir("refine-until");
  const std::string scene = source_path("examples/goodman-toppling-creep.yaml");
  const std::string file = (dir / "r.yaml").string();
  st::RefinementOptions o;
  o.until = 20.0;
  const auto r = st::refinement_study(scene, file, o);
  BOOST_TEST_REQUIRE(r.study.cases.size() == 4u);
  for (const auto& c : r.study.cases) {
    BOOST_TEST_REQUIRE(find(c, "analysis.duration") != nullptr);
    BOOST_TEST(find(c, "analysis.duration")->value_yaml == "20");
  }
  BOOST_TEST(r.study.times == (std::vector<double>{10.0, 20.0}), boost::test_tools::per_element());
  o.until = 0.005;  // inside the settling stage (until 0.01 d)
  BOOST_CHECK_THROW(st::refinement_study(scene, file, o), std::invalid_argument);
  o.until = 200.0;  // after the duration
  BOOST_CHECK_THROW(st::refinement_study(scene, file, o), std::invalid_argument);
  o.until.reset();
  o.levels = 1;
  BOOST_CHECK_THROW(st::refinement_study(scene, file, o), std::invalid_argument);
}

BOOST_AUTO_TEST_CASE(a_settling_stage_that_ends_at_rest_bounds_no_until) {
  // The bench slope's settling stage has no `until`: it ends at rest (rest_tolerance), its
  // longest the analysis's duration. Where it ends is the run's to find, so the study
  // compares the levels at the duration, or at an earlier --until, as for any scene.
  const fs::path dir = fresh_dir("refine-rest");
  const std::string scene = source_path("bench/scenes/jointed-slope-cohesionless.yaml");
  const std::string file = (dir / "r.yaml").string();
  st::RefinementOptions o;
  const auto r = st::refinement_study(scene, file, o);
  BOOST_TEST_REQUIRE(r.study.cases.size() == 4u);
  o.until = 50.0;
  const auto half = st::refinement_study(scene, file, o);
  for (const auto& c : half.study.cases) {
    BOOST_TEST_REQUIRE(find(c, "analysis.duration") != nullptr);
    BOOST_TEST(find(c, "analysis.duration")->value_yaml == "50");
  }
}

BOOST_AUTO_TEST_CASE(the_verdict_follows_the_levels) {
  const st::RefinementOptions o;  // tolerance 5 %, converged 1 %
  {  // Converging to first order towards 1: 1 + 0.16 / 2^k. L0 is 16 % off the limit.
    const auto r = synthetic(6, 1);
    const auto a = st::assess_refinement(r, results({{1.16, 1.08, 1.04, 1.02, 1.01, 1.005}}), o);
    BOOST_TEST(static_cast<int>(a.verdict) == static_cast<int>(st::RefinementVerdict::coarse));
    BOOST_TEST(a.quantities[0].extrapolated);
    BOOST_TEST(a.quantities[0].reference == 1.0, boost::test_tools::tolerance(1e-12));
    BOOST_TEST(a.quantities[0].error == 0.16 / 1.16, boost::test_tools::tolerance(1e-12));
    // 1.04 is 3.4 % of 1.16 from the limit, 1.08 6.9 %: level L2 is the first fine one.
    BOOST_TEST(a.recommended_level == 2);
    BOOST_TEST(a.message.find("L2") != std::string::npos, a.message);
  }
  {  // Converged at L0 already.
    const auto r = synthetic(4, 1);
    const auto a = st::assess_refinement(r, results({{1.0, 1.001, 1.0015, 1.00175}}), o);
    BOOST_TEST(static_cast<int>(a.verdict) == static_cast<int>(st::RefinementVerdict::fine));
    BOOST_TEST(a.largest_error < 0.01);
  }
  {  // Wandering: no limit.
    const auto r = synthetic(4, 1);
    const auto a = st::assess_refinement(r, results({{1.0, 1.2, 0.9, 1.1}}), o);
    BOOST_TEST(static_cast<int>(a.verdict) == static_cast<int>(st::RefinementVerdict::not_converged));
    BOOST_TEST(a.recommended_level == -1);
  }
  {  // The same sequence one level shorter: the last three levels differ by 1.7 % and 0.86 %.
    const auto r = synthetic(5, 1);
    const auto a = st::assess_refinement(r, results({{1.16, 1.08, 1.04, 1.02, 1.01}}), o);
    BOOST_TEST(static_cast<int>(a.verdict) == static_cast<int>(st::RefinementVerdict::not_converged));
  }
  {  // Two levels agree by chance after an event at the level before: not converged.
    const auto r = synthetic(5, 1);
    const auto a = st::assess_refinement(r, results({{3.10, 3.21, 3.17, 3.10, 3.1002}}), o);
    BOOST_TEST(static_cast<int>(a.verdict) == static_cast<int>(st::RefinementVerdict::not_converged));
  }
  {  // The last two agree within 1 % but the differences grow: not converged.
    const auto r = synthetic(4, 1);
    const auto a = st::assess_refinement(r, results({{1.0, 1.0, 1.002, 1.01}}), o);
    BOOST_TEST(static_cast<int>(a.verdict) == static_cast<int>(st::RefinementVerdict::not_converged));
  }
  {  // Scatter below 0.5 % that does not shrink (the shipped toppling example:
     // block 10 at 3.276-3.281 m over six levels): converged, fine.
    const auto r = synthetic(6, 1);
    const auto a = st::assess_refinement(r, results({{3.281, 3.2786, 3.2810, 3.2764, 3.2762, 3.2890}}), o);
    BOOST_TEST(static_cast<int>(a.verdict) == static_cast<int>(st::RefinementVerdict::fine));
  }
  {  // A quantity below 1 % of the largest displacement is shown, not judged.
    const auto r = synthetic(4, 2);
    const auto a = st::assess_refinement(r, results({{1.0, 1.0, 1.0, 1.0}, {1e-6, 3e-6, 2e-6, 5e-7}}), o);
    BOOST_TEST(!a.quantities[1].judged);
    BOOST_TEST(static_cast<int>(a.verdict) == static_cast<int>(st::RefinementVerdict::fine));
  }
  {  // A failed level, or one that did not reach the time: nothing to compare.
    const auto r = synthetic(3, 1);
    auto res = results({{1.0, 1.0, 1.0}});
    res[1].status = "failed";
    res[1].message = "step 7: singular";
    auto a = st::assess_refinement(r, res, o);
    BOOST_TEST(static_cast<int>(a.verdict) == static_cast<int>(st::RefinementVerdict::incomplete));
    BOOST_TEST(a.message.find("step 7: singular") != std::string::npos, a.message);
    res[1].status = "completed";
    res[2].values[0].reset();
    a = st::assess_refinement(r, res, o);
    BOOST_TEST(static_cast<int>(a.verdict) == static_cast<int>(st::RefinementVerdict::incomplete));
  }
}

BOOST_AUTO_TEST_CASE(check_refine_says_a_coarse_step_is_coarse_and_a_fine_one_fine) {
  const fs::path dir = fresh_dir("refine-cli");
  {
    const fs::path scene = ramped_creep_test(dir, "50");
    const auto r = run_rheodda("check " + scene.string() + " --refine=5 -j 2 -o " + (dir / "coarse").string());
    BOOST_TEST(r.exit_code == 3, r.output);
    BOOST_TEST(r.output.find("step controls: coarse") != std::string::npos, r.output);
    BOOST_TEST(r.output.find("Level L1 is the first within 5 %") != std::string::npos, r.output);
    BOOST_TEST(fs::exists(dir / "coarse" / "refinement.txt"));
    const std::string json = read_text((dir / "coarse" / "refinement.json").string());
    BOOST_TEST(json.find("\"verdict\": \"coarse\"") != std::string::npos, json);
    BOOST_TEST(json.find("\"recommended_level\": 1") != std::string::npos, json);
    BOOST_TEST(fs::exists(dir / "coarse" / "study.csv"));
    // The levels' joint displacement at 200 h against the creep of the ramp in closed
    // form: the ramp's Burgers response, d(t) = F'(t/E1 + t^2/(2 eta1) + t/E2 - eta2/E2^2 (1 - exp(-E2 t/eta2))),
    // per unit joint area (F' = 0.232/200 MPa/h); the finest level (dt 3.125 h) is within 0.5 %.
    const double E1 = 26.87, E2 = 192.43, eta1 = 34807.72, eta2 = 2141.23, rate = 0.232 / 200.0, t = 200.0;
    const double closed =
        rate * (t / E1 + t * t / (2 * eta1) + t / E2 - eta2 / (E2 * E2) * (1 - std::exp(-E2 * t / eta2)));
    const auto rows = read_study_csv((dir / "coarse" / "study.csv").string());
    BOOST_TEST_REQUIRE(rows.size() == 5u);
    const double finest = std::stod(rows[4].at("plane.shear_displacement_magnitude@200"));
    const double coarse = std::stod(rows[0].at("plane.shear_displacement_magnitude@200"));
    BOOST_TEST(std::abs(finest - closed) / closed < 0.005, "finest " << finest << " closed form " << closed);
    BOOST_TEST(std::abs(coarse - closed) / closed > 0.01);  // dt 50 h is visibly off
  }
  {
    const fs::path scene = ramped_creep_test(dir, "10");
    const auto r = run_rheodda("check " + scene.string() + " --refine=4 -j 2 -o " + (dir / "fine").string());
    BOOST_TEST(r.exit_code == 0, r.output);
    BOOST_TEST(r.output.find("step controls: fine") != std::string::npos, r.output);
  }
  {  // Refinement options without --refine are refused, not ignored.
    const auto r = run_rheodda("check " + source_path("examples/shear-creep-test.yaml") + " -o " +
                               (dir / "nothing").string());
    BOOST_TEST(r.exit_code == 2, r.output);
    BOOST_TEST(!fs::exists(dir / "nothing"));
  }
}

BOOST_AUTO_TEST_SUITE_END()
