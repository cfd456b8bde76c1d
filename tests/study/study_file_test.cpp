// Study files: a bad study is refused whole, before anything runs, with the study
// file, line, column and key; `rheodda study` then exits 2 and runs nothing.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "rheodda/scene/loader.hpp"
#include "rheodda/study/study.hpp"
#include "study_support.hpp"

using namespace rheodda::study_test;
namespace st = rheodda::study;
namespace fs = std::filesystem;

namespace {

/// A valid study of the sliding block; line numbers (1-based) are relied on below.
std::string study_text() {
  return "scene: " + source_path("examples/sliding-block.yaml") + "\n"  // 1
         "set: {analysis.duration: 0.05}\n"                              // 2
         "outputs: [centre.u, slope.shear_displacement]\n"               // 3
         "times: [0.01, 0.05]\n"                                         // 4
         "cases:\n"                                                      // 5
         "  - name: phi10\n"                                             // 6
         "    set: {joint_sets.slope.friction_angle: 10}\n"              // 7
         "  - {name: phi20}\n";                                          // 8
}

/// Loading `text` and building its cases must fail at `line` with `key_part` and `message_part`.
void expect_study_error(const std::string& text, int line, const std::string& key_part, const std::string& message_part) {
  try {
    const auto s = st::parse_study(text, "bad-study.yaml");
    (void)st::prepare_cases(s);
    BOOST_ERROR("no error for a study expected to fail with '" << message_part << "'");
  } catch (const st::SceneError& e) {
    BOOST_TEST_INFO("error: " << e.what());
    BOOST_TEST(e.file() == "bad-study.yaml");
    BOOST_TEST(e.line() == line);
    BOOST_TEST(e.key().find(key_part) != std::string::npos);
    BOOST_TEST(e.message().find(message_part) != std::string::npos);
  }
}

}  // namespace

BOOST_AUTO_TEST_SUITE(study_file)

BOOST_AUTO_TEST_CASE(a_valid_study_builds_one_scene_per_case_with_the_overrides_applied) {
  const auto s = st::parse_study(study_text(), "ok.yaml");
  BOOST_TEST(s.cases.size() == 2u);
  BOOST_TEST(s.plot == "centre.u");  // default: the first output
  const auto texts = st::prepare_cases(s);
  BOOST_TEST_REQUIRE(texts.size() == 2u);
  BOOST_TEST(texts[0].find("friction_angle: 10") != std::string::npos, texts[0]);
  BOOST_TEST(texts[1].find("friction_angle: 20") != std::string::npos, texts[1]);
  for (const auto& t : texts) BOOST_TEST(t.find("duration: 0.05") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(a_case_writes_what_the_study_reads_its_times_as_output_times_and_no_frames) {
  // docs/guide/studies.md, "What a case writes".
  const auto s = st::parse_study(study_text(), "ok.yaml");
  BOOST_TEST(!s.frames);
  const auto texts = st::prepare_cases(s);
  const auto c = rheodda::scene::parse_scene(texts[0], "case");
  BOOST_TEST(c.analysis.output_times == (std::vector<double>{0.01, 0.05}), boost::test_tools::per_element());
  BOOST_TEST(!c.analysis.frames);
  // The study asks for frames; a case's own `analysis.frames` wins; times the base scene
  // lists already are kept, those after a case's duration are left to the study's check.
  const std::string framed = study_text() + "frames: true\n";
  const auto f = st::parse_study(framed, "framed.yaml");
  BOOST_TEST(f.frames);
  BOOST_TEST(rheodda::scene::parse_scene(st::prepare_cases(f)[0], "case").analysis.frames);
  std::string own = study_text();
  own.replace(own.find("{joint_sets.slope.friction_angle: 10}"), 37,
              "{joint_sets.slope.friction_angle: 10, analysis.frames: true, analysis.output_times: [0.02, 0.05]}");
  const auto o = st::parse_study(own, "own.yaml");
  const auto oc = rheodda::scene::parse_scene(st::prepare_cases(o)[0], "case");
  BOOST_TEST(oc.analysis.frames);
  BOOST_TEST(oc.analysis.output_times == (std::vector<double>{0.01, 0.02, 0.05}), boost::test_tools::per_element());
  expect_study_error(study_text() + "frames: some\n", 9, "frames", "expected true or false");
}

BOOST_AUTO_TEST_CASE(a_study_reads_the_displacement_after_settling) {
  // docs/reference/outputs.md, "Displacement after settling": with a settling stage a
  // point's POINT.u_after_settling and POINT.displacement_after_settling are outputs.
  const fs::path dir = fresh_dir("after-settling-study");
  std::string scene = read_text(source_path("examples/shear-creep-test.yaml"));
  scene.replace(scene.find("  output_interval: 2     # h\n"), 29, "  output_interval: 50\n  settle: {until: 1, dt: 0.25}\n");
  std::ofstream(dir / "settle.yaml") << scene;
  std::ofstream(dir / "study.yaml") << "scene: settle.yaml\n"
                                       "outputs: [A_joint.displacement, A_joint.displacement_after_settling, A_joint.u_after_settling]\n"
                                       "times: [1, 100, 200]\n"
                                       "cases:\n"
                                       "  - {name: base}\n";
  const auto r = run_rheodda("study " + (dir / "study.yaml").string() + " -o " + (dir / "out").string() + " --no-plot");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.output);
  const auto row = read_study_csv((dir / "out" / "study.csv").string()).at(0);
  BOOST_TEST(std::stod(row.at("A_joint.displacement_after_settling@1")) == 0.0);  // the settling's end
  const double settled = std::stod(row.at("A_joint.displacement@1"));
  BOOST_TEST(settled > 0.005);
  // After it: the creep alone, 2.4e-3 mm of the 11.2e-3 mm at 200 h.
  BOOST_TEST(std::stod(row.at("A_joint.u_after_settling@200")) > 0.002);
  BOOST_TEST(std::stod(row.at("A_joint.displacement_after_settling@200")) <
             std::stod(row.at("A_joint.displacement@200")) - 0.9 * settled);
  // A scene without a settling stage has no such output: refused before anything runs.
  std::ofstream(dir / "plain.yaml") << "scene: " << source_path("examples/shear-creep-test.yaml") << "\n"
                                       "outputs: [A_joint.displacement_after_settling]\n"
                                       "times: [200]\n"
                                       "cases:\n"
                                       "  - {name: base}\n";
  try {
    (void)st::prepare_cases(st::load_study((dir / "plain.yaml").string()));
    BOOST_ERROR("a study of a column the run will not have was accepted");
  } catch (const st::SceneError& e) {
    BOOST_TEST(std::string(e.what()).find("has no history column 'A_joint.displacement_after_settling'") != std::string::npos,
               e.what());
  }
}

BOOST_AUTO_TEST_CASE(overrides_select_map_keys_list_elements_by_index_or_name_and_remove_keys) {
  const std::string base = read_text(source_path("examples/goodman-toppling.yaml"));
  const auto s = st::parse_study(
      "scene: " + source_path("examples/goodman-toppling.yaml") + "\n"
      "outputs: [block1_top.u]\n"
      "times: [1]\n"
      "cases:\n"
      "  - name: edited\n"
      "    set:\n"
      "      blocks[2].fixed: true\n"
      "      blocks[block3].fixed: true\n"
      "      joint_sets.base.law: ~\n"
      "      joint_sets.base.shear_stiffness: 2.5e8\n"
      "      joint_sets.anti_toppling.law: {name: maxwell, E1: 2.0e8, eta1: 3.0e8}\n"
      "      analysis.scheme: lagged\n",
      "edit.yaml");
  const auto c = rheodda::scene::parse_scene(st::case_scene_text(s, base, s.cases[0]), "case");
  BOOST_TEST_REQUIRE(c.blocks.size() == 17u);
  BOOST_TEST(c.blocks[2].name == "block2");
  BOOST_TEST(c.blocks[2].fixed);
  BOOST_TEST(c.blocks[3].name == "block3");
  BOOST_TEST(c.blocks[3].fixed);
  BOOST_TEST(!c.blocks[4].fixed);
  const auto& jb = c.joint_sets[0];
  const auto& ja = c.joint_sets[1];
  BOOST_TEST(jb.name == "base");
  BOOST_TEST(!jb.law.has_value());
  BOOST_TEST(jb.shear_stiffness.value_or(0.0) == 2.5e8);
  BOOST_TEST(jb.friction_angle == 50.0);  // untouched keys keep their base values
  BOOST_TEST_REQUIRE(ja.law.has_value());
  BOOST_TEST(ja.law->name == "maxwell");
  BOOST_TEST(ja.law->parameters.at("E1") == 2.0e8);
  BOOST_TEST(ja.law->parameters.at("eta1") == 3.0e8);
  BOOST_TEST((c.analysis.scheme == rheodda::laws::Scheme::lagged));

  const auto fails = [&](const std::string& key, const std::string& message_part) {
    const auto bad = st::parse_study("scene: " + source_path("examples/goodman-toppling.yaml") +
                                         "\noutputs: [block1_top.u]\ntimes: [1]\ncases:\n  - name: x\n    set:\n      " +
                                         key + "\n",
                                     "bad.yaml");
    try {
      (void)st::case_scene_text(bad, base, bad.cases[0]);
      BOOST_ERROR("no error for " << key);
    } catch (const st::SceneError& e) {
      BOOST_TEST_INFO(e.what());
      BOOST_TEST(e.line() == 7);
      BOOST_TEST(e.message().find(message_part) != std::string::npos);
    }
  };
  fails("blocks[17].fixed: true", "has 17 elements");
  fails("blocks[nosuch].fixed: true", "no element named 'nosuch'");
  fails("joint_sets.base.cohesionx: ~", "no 'joint_sets.base.cohesionx' to remove");
  fails("joint_sets.nosuch.friction_angle: 30", "no 'joint_sets.nosuch'");
  fails("analysis.dt.x: 1", "not a map");
}

BOOST_AUTO_TEST_CASE(bad_study_files_are_refused_with_line_and_key) {
  const std::string ok = study_text();
  expect_study_error(with("cases:\n", "case_list: []\ncases:\n", ok), 5, "case_list", "unknown key");
  expect_study_error(with("slope.friction_angle: 10", "slopes.friction_angle: 10", ok), 7,
                     "joint_sets.slopes.friction_angle", "no 'joint_sets.slopes'");
  // A value the scene loader refuses is located at the override that set it.
  expect_study_error(with("friction_angle: 10", "friction_angle: 95", ok), 7, "joint_sets.slope.friction_angle",
                     "out of range");
  expect_study_error(with("centre.u,", "centre.w,", ok), 6, "outputs[0]", "no history column 'centre.w'");
  expect_study_error(with("times: [0.01, 0.05]", "times: [0.01, 0.5]", ok), 6, "times", "after the end");
  expect_study_error(with("  - {name: phi20}", "  - {name: phi10}", ok), 8, "cases[1].name", "given twice");
  expect_study_error(with("name: phi10", "name: ../x", ok), 6, "cases[0].name", "folder name");
  expect_study_error(with("times: [0.01, 0.05]", "times: [0.01, x]", ok), 4, "times[1]", "not a number");
}

BOOST_AUTO_TEST_CASE(a_misspelt_study_key_gets_the_nearest_valid_one_as_in_a_scene) {
  // The study file's maps are checked by the scene reader's map reader (scene/src/yaml_reader.hpp):
  // file, line, column, the key, "did you mean" the nearest valid key, and the valid keys.
  const std::string ok = study_text();
  const auto error_of = [](const std::string& text) {
    try {
      (void)st::parse_study(text, "typo.yaml");
    } catch (const st::SceneError& e) {
      return e;
    }
    throw std::runtime_error("no error for a study with a misspelt key");
  };
  const auto top = error_of(with("times:", "tims:", ok));
  BOOST_TEST(top.what() == std::string("typo.yaml:4:1: tims: unknown key 'tims' (did you mean 'times'?); valid keys "
                                       "here: title, scene, set, outputs, times, plot, frames, cases, sweep"));
  const auto in_case = error_of(with("  - {name: phi20}", "  - {nmae: phi20}", ok));
  BOOST_TEST(in_case.line() == 8);
  BOOST_TEST(in_case.column() == 6);
  BOOST_TEST(in_case.key() == "cases[1].nmae");
  BOOST_TEST(in_case.message() == "unknown key 'nmae' (did you mean 'name'?); valid keys here: name, set");
  const auto in_sweep = error_of(ok + "sweep:\n  method: random\n  sampels: 3\n"
                                      "  parameters: [{key: analysis.dt, unit: s, range: [0.001, 0.01]}]\n");
  BOOST_TEST(in_sweep.line() == 11);
  BOOST_TEST(in_sweep.column() == 3);
  BOOST_TEST(in_sweep.key() == "sweep.sampels");
  BOOST_TEST(in_sweep.message().find("unknown key 'sampels' (did you mean 'samples'?)") == 0u, in_sweep.message());
  const auto in_parameter = error_of(ok + "sweep:\n  parameters: [{key: analysis.dt, unit: s, valeus: [0.001]}]\n");
  BOOST_TEST(in_parameter.key() == "sweep.parameters[0].valeus");
  BOOST_TEST(in_parameter.message().find("(did you mean 'values'?)") != std::string::npos, in_parameter.message());
  // A word near none of the valid keys gets no suggestion; a key given twice is refused at its second place.
  BOOST_TEST(error_of(with("times:", "zzzzzz:", ok)).message().find("unknown key 'zzzzzz'; valid keys here:") == 0u);
  const auto twice = error_of(ok + "times: [0.02]\n");
  BOOST_TEST(twice.line() == 9);
  BOOST_TEST(twice.key() == "times");
  BOOST_TEST(twice.message() == "key 'times' is given twice (first at line 4)");
}

BOOST_AUTO_TEST_CASE(times_and_overrides_may_carry_their_units) {
  // sliding-block.yaml is in m, N, s: 10 ms is 0.01 s; an override's unit is the case scene's to convert.
  const std::string ok = study_text();
  const auto s = st::parse_study(with("times: [0.01, 0.05]", "times: [10 ms, 0.05]",
                                      with("friction_angle: 10}", "friction_angle: 0.2 rad}", ok)),
                                 "units.yaml");
  BOOST_TEST(s.times[0] == 0.01, boost::test_tools::tolerance(1e-15));
  BOOST_TEST(s.times[1] == 0.05);
  const auto texts = st::prepare_cases(s);
  const auto phi = rheodda::scene::parse_scene(texts[0], "case.yaml").joint_sets[0].friction_angle;
  BOOST_TEST(phi == 0.2 * 180.0 / std::acos(-1.0), boost::test_tools::tolerance(1e-14));
  expect_study_error(with("times: [0.01, 0.05]", "times: [0.01, 5 m]", ok), 4, "times[1]",
                     "m is length, this key takes time");

  // A sweep's values are in its `unit`: kPa into the scene's N/m^2, ms into its s; a
  // label UDUNITS-2 does not know leaves them in the scene's units.
  const std::string sweep = "scene: " + source_path("examples/sliding-block.yaml") +
                            "\noutputs: [centre.u]\ntimes: [0.01]\nsweep:\n  parameters:\n"
                            "    - {name: c, key: joint_sets.slope.cohesion, unit: kPa, values: [2, 5]}\n"
                            "    - {name: dt, key: analysis.dt, unit: ms, values: [0.5]}\n"
                            "    - {name: phi, key: joint_sets.slope.friction_angle, unit: degrees-label, values: [25]}\n";
  const auto w = st::parse_study(sweep, "sweep.yaml");
  const auto cases = st::prepare_cases(w);
  BOOST_TEST_REQUIRE(cases.size() == 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    const auto c = rheodda::scene::parse_scene(cases[k], "case.yaml");
    BOOST_TEST(c.joint_sets[0].cohesion == (k == 0 ? 2000.0 : 5000.0), boost::test_tools::tolerance(1e-12));
    BOOST_TEST(c.analysis.dt == 5e-4, boost::test_tools::tolerance(1e-12));
    BOOST_TEST(c.joint_sets[0].friction_angle == 25.0);
  }
  BOOST_TEST(w.parameters[0].values == (std::vector<double>{2, 5}));  // study.csv's column stays in kPa
}

BOOST_AUTO_TEST_CASE(rheodda_study_exits_2_on_a_bad_study_and_runs_nothing) {
  const fs::path dir = fresh_dir("bad");
  const fs::path file = dir / "bad.yaml";
  std::ofstream(file) << with("friction_angle: 10", "friction_angle: 95", study_text());
  const auto r = run_rheodda("study " + file.string() + " -o " + (dir / "out").string());
  BOOST_TEST(r.exit_code == 2, r.output);
  BOOST_TEST(r.output.find(file.string() + ":7:") != std::string::npos, r.output);
  BOOST_TEST(!fs::exists(dir / "out" / "cases"));
  BOOST_TEST(run_rheodda("study " + (dir / "missing.yaml").string()).exit_code == 2);
}

BOOST_AUTO_TEST_CASE(every_shipped_study_loads_and_each_of_its_cases_is_a_valid_scene) {
  // examples/studies/*.yaml: what docs/guide/studies.md tells users to run (the folder also
  // holds forecast-slope.yaml, a scene for `rheodda forecast`: no `scene:` line).
  int studies = 0;
  for (const auto& e : fs::directory_iterator(source_path("examples/studies"))) {
    if (e.path().extension() != ".yaml") continue;
    const std::string text = read_text(e.path().string());
    if (text.find("\nscene: ") == std::string::npos) continue;
    BOOST_TEST_CONTEXT(e.path().filename().string()) {
      ++studies;
      const auto s = st::load_study(e.path().string());
      const auto texts = st::prepare_cases(s);
      BOOST_TEST_REQUIRE(texts.size() == s.cases.size());
      BOOST_TEST(!texts.empty());
      for (std::size_t k = 0; k < texts.size(); ++k)
        BOOST_CHECK_NO_THROW((void)rheodda::scene::parse_scene(texts[k], "case " + s.cases[k].name));
    }
  }
  BOOST_TEST(studies >= 4);
}

BOOST_AUTO_TEST_CASE(a_case_scene_is_titled_by_the_base_title_and_the_case_changes) {
  // The shipped phi sweep: every case removes the base's Burgers laws, so its title must not
  // be the base scene's "...with Burgers creep on its joints (phi = 50 deg)" alone.
  const auto s = st::load_study(source_path("examples/studies/toppling-phi.yaml"));
  const auto texts = st::prepare_cases(s);
  BOOST_TEST_REQUIRE(texts.size() == s.cases.size());
  const auto phi33 = rheodda::scene::parse_scene(texts[0], "case phi33");
  const std::string base = "Goodman toppling slope with Burgers creep on its joints (phi = 50 deg)";
  BOOST_TEST(phi33.title ==
             base + " [case phi33: joint_sets.base.friction_angle = 33, joint_sets.base.law removed, "
                    "joint_sets.base.shear_stiffness = 1.0e8, joint_sets.base.restitution = 0, "
                    "joint_sets.anti_toppling.law removed, joint_sets.anti_toppling.shear_stiffness = 1.0e8, "
                    "joint_sets.anti_toppling.restitution = 0, materials.rock.damping_ratio = 1, "
                    "analysis.type = dynamic, analysis.settle removed, analysis.scheme removed, "
                    "analysis.duration = 2.3148148e-4, "
                    "analysis.dt = 5.787037e-9, analysis.output_interval = 1.1574074e-5, "
                    "analysis.max_displacement_ratio = 0.00025]");
  // Each case's title differs by its own change, listed first.
  const auto phi55 = rheodda::scene::parse_scene(texts.back(), "case phi55");
  BOOST_TEST(phi55.title.find(base + " [case phi55: joint_sets.base.friction_angle = 55, ") == 0u, phi55.title);

  // A case without changes names itself; a case that sets `title` keeps its own.
  const auto own = st::parse_study("scene: " + source_path("examples/sliding-block.yaml") +
                                       "\noutputs: [centre.u]\ntimes: [0.01]\ncases:\n  - {name: plain}\n"
                                       "  - {name: named, set: {title: My own title}}\n",
                                   "own.yaml");
  const std::string base_text = read_text(source_path("examples/sliding-block.yaml"));
  const std::string sliding_title = rheodda::scene::parse_scene(base_text, "base").title;
  BOOST_TEST(rheodda::scene::parse_scene(st::case_scene_text(own, base_text, own.cases[0]), "c").title ==
             sliding_title + " [case plain]");
  BOOST_TEST(rheodda::scene::parse_scene(st::case_scene_text(own, base_text, own.cases[1]), "c").title ==
             "My own title");
}

BOOST_AUTO_TEST_CASE(a_missing_study_or_base_scene_is_named_with_the_reason_and_no_bogus_location) {
  const fs::path dir = fresh_dir("missing");
  const std::string missing = (dir / "missing.yaml").string();
  const auto r = run_rheodda("study " + missing);
  BOOST_TEST(r.exit_code == 2);
  BOOST_TEST(r.output.find("rheodda: error: cannot open " + missing + ": No such file or directory") !=
                 std::string::npos, r.output);
  BOOST_TEST(r.output.find(":0:0") == std::string::npos, r.output);
  // A base scene that cannot be opened: located at the study's `scene:` value (line 1, column 8).
  const fs::path file = dir / "study.yaml";
  std::ofstream(file) << "scene: nosuch.yaml\noutputs: [centre.u]\ntimes: [0.01]\ncases:\n  - {name: a}\n";
  const auto b = run_rheodda("study " + file.string() + " -o " + (dir / "out").string());
  BOOST_TEST(b.exit_code == 2);
  BOOST_TEST(b.output.find(file.string() + ":1:8: scene: cannot open " + (dir / "nosuch.yaml").string() +
                           ": No such file or directory") != std::string::npos, b.output);
  BOOST_TEST(b.output.find(":0:0") == std::string::npos, b.output);
}

BOOST_AUTO_TEST_CASE(a_study_takes_every_column_of_the_runs_history_bolts_and_stage_included) {
  // The study checks its outputs against the run's own list of columns (scene::history_columns):
  // the bolts' energy columns and `stage` of a scene with bolts and stages are there too.
  const fs::path dir = fresh_dir("bolt-stage-columns");
  std::ofstream(dir / "bolted.yaml") << read_text(source_path("examples/bolted-block.yaml"))
                                     << "\nstages:\n"
                                        "  - {name: weaken, at: 0.3, joint_sets: {slope: {friction_angle: 15}}}\n"
                                        "  - {name: weaker, at: 0.6, joint_sets: {slope: {friction_angle: 10}}}\n";
  std::ofstream(dir / "study.yaml") << "scene: bolted.yaml\n"
                                       "outputs: [energy_bolt, dissipation_bolt, stage]\n"
                                       "times: [0.2, 0.5, 1.0]\n"
                                       "cases:\n"
                                       "  - {name: phi20}\n";
  const auto r = run_rheodda("study " + (dir / "study.yaml").string() + " -o " + (dir / "out").string() + " --no-plot");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.output);
  const auto rows = read_study_csv((dir / "out" / "study.csv").string());
  BOOST_TEST_REQUIRE(rows.size() == 1u);
  const auto& row = rows[0];
  for (const auto& [column, text] : row) BOOST_TEST_MESSAGE(column << " = " << text);
  // `stage` as a number: the stages begun by that time (0 before the first; docs/guide/studies.md).
  BOOST_TEST(std::stod(row.at("stage@0.2")) == 0.0);
  BOOST_TEST(std::stod(row.at("stage@0.5")) == 1.0);
  BOOST_TEST(std::stod(row.at("stage@1")) == 2.0);
  // The bolt columns at the end: the values of the case's own history.csv, last row.
  std::ifstream history(dir / "out" / "cases" / "phi20" / "history.csv");
  std::string line, header, last;
  while (std::getline(history, line))
    if (!line.empty() && line[0] != '#') (header.empty() ? header : last) = line;
  auto field = [](const std::string& text, std::size_t k) {
    std::stringstream in(text);
    std::string f;
    for (std::size_t i = 0; i <= k; ++i) std::getline(in, f, ',');
    return f;
  };
  auto index_of = [&](const std::string& name) {
    std::stringstream in(header);
    std::string f;
    for (std::size_t i = 0; std::getline(in, f, ','); ++i)
      if (f == name) return i;
    BOOST_FAIL("history.csv has no column " << name);
    return std::size_t{0};
  };
  for (const char* column : {"energy_bolt", "dissipation_bolt"}) {
    const double run = std::stod(field(last, index_of(column)));
    BOOST_TEST(run > 0.0, column);  // the bolt holds the block: its spring stores and dissipates energy
    BOOST_TEST(std::stod(row.at(std::string(column) + "@1")) == run, boost::test_tools::tolerance(1e-9));
  }
}

BOOST_AUTO_TEST_SUITE_END()
