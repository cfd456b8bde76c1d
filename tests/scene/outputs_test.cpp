// Outputs sized to the question (docs/reference/outputs.md, "Output times" and
// "history.csv"): a step ends on each output time, history.csv has its rows there
// (every step on request), `frames: false` writes no frames, and the measurement
// points' displacement after the settling stage.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>

#include "run_support.hpp"
#include "rheodda/scene/describe.hpp"
#include "rheodda/scene/loader.hpp"
#include "rheodda/scene/output.hpp"
#include "rheodda/scene/plot.hpp"
#include "rheodda/scene/run.hpp"

using namespace rheodda;
using namespace rheodda::test;
namespace fs = std::filesystem;

namespace {

/// history.csv as its header and rows of cells.
struct History {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::size_t column(const std::string& name) const {
    for (std::size_t i = 0; i < header.size(); ++i)
      if (header[i] == name) return i;
    BOOST_FAIL("history.csv has no column " << name);
    return 0;
  }
  bool has(const std::string& name) const { return std::find(header.begin(), header.end(), name) != header.end(); }
  double at(std::size_t row, const std::string& name) const { return std::stod(rows.at(row).at(column(name))); }
  std::string cell(std::size_t row, const std::string& name) const { return rows.at(row).at(column(name)); }
};

std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> out;
  std::string c;
  std::stringstream ss(line);
  while (std::getline(ss, c, ',')) out.push_back(c);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

History read_history(const fs::path& out) {
  History h;
  std::istringstream in(read_text((out / "history.csv").string()));
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (h.header.empty())
      h.header = cells(line);
    else
      h.rows.push_back(cells(line));
  }
  return h;
}

/// The times blocks.pvd lists.
std::vector<double> frame_times(const fs::path& out) {
  const std::string pvd = read_text((out / "blocks.pvd").string());
  const std::regex entry("timestep=\"([^\"]+)\"");
  std::vector<double> t;
  for (auto it = std::sregex_iterator(pvd.begin(), pvd.end(), entry); it != std::sregex_iterator(); ++it)
    t.push_back(std::stod((*it)[1].str()));
  return t;
}

bool near(double a, double b, double scale) { return std::abs(a - b) <= 1e-9 * std::max(1.0, std::abs(scale)); }

/// The shear creep test (examples/shear-creep-test.yaml) under adaptive creep stepping
/// from 0.1 h, output every `interval` h.
scene::SceneDescription adaptive_creep(double interval) {
  auto s = scene::load_scene(source_path("examples/shear-creep-test.yaml"));
  s.analysis.dt = 0.1;
  s.analysis.creep_tolerance = 1e-6;  // mm
  s.analysis.output_interval = interval;
  return s;
}

/// The shear creep test (examples/shear-creep-test.yaml: a block loaded on a Burgers
/// joint) with a settling stage of 1 h at steps of 0.25 h, outputs every 50 h.
std::string settling_scene() {
  return with("  output_interval: 2     # h\n", "  output_interval: 50\n  settle: {until: 1, dt: 0.25}\n",
              read_text(source_path("examples/shear-creep-test.yaml")));
}

}  // namespace

BOOST_AUTO_TEST_SUITE(outputs)

BOOST_AUTO_TEST_CASE(the_output_keys_are_read_and_checked_with_file_line_and_column) {
  const auto s = scene::parse_scene(with("  dt: 0.01\n", "  dt: 0.01\n  output_times: [0.255, 0.6]\n  history: steps\n  frames: false\n"),
                                    "ok.yaml");
  BOOST_TEST(s.analysis.output_times == (std::vector<double>{0.255, 0.6}), boost::test_tools::per_element());
  BOOST_TEST((s.analysis.history == scene::HistoryRows::steps));
  BOOST_TEST(!s.analysis.frames);
  const auto d = scene::parse_scene(kBaseScene, "default.yaml");  // the defaults
  BOOST_TEST(d.analysis.output_times.empty());
  BOOST_TEST((d.analysis.history == scene::HistoryRows::outputs));
  BOOST_TEST(d.analysis.frames);
  // The output times: 0, every output_interval (duration / 100), the listed ones, the end.
  const auto t = scene::run_output_times(s.analysis);
  BOOST_TEST(t.size() == 102u);  // 0.6 is 60 x 0.01 as well: counted once
  BOOST_TEST(std::count(t.begin(), t.end(), 0.255) == 1);
  BOOST_TEST(t.back() == 1.0);

  const std::string unordered = with("  dt: 0.01\n", "  dt: 0.01\n  output_times: [0.5, 0.25]\n");
  expect_error_at(unordered, 5, "0.25", "analysis.output_times[1]", "0.25 does not follow 0.5: output times are strictly increasing");
  const std::string after = with("  dt: 0.01\n", "  dt: 0.01\n  output_times: [0.5, 2]\n");
  expect_error_at(after, 5, "2]", "analysis.output_times[1]", "out of range");
  const std::string zero = with("  dt: 0.01\n", "  dt: 0.01\n  output_times: [0]\n");
  expect_error_at(zero, 5, "0]", "analysis.output_times[0]", "out of range");
  const std::string scalar = with("  dt: 0.01\n", "  dt: 0.01\n  output_times: 0.5\n");
  expect_error_at(scalar, 5, "0.5", "analysis.output_times", "expected a list of times");
  const std::string history = with("  dt: 0.01\n", "  dt: 0.01\n  history: every\n");
  expect_error_at(history, 5, "every", "analysis.history", "outputs");
  const std::string frames = with("  dt: 0.01\n", "  dt: 0.01\n  frames: none\n");
  expect_error_at(frames, 5, "none", "analysis.frames", "true");
}

BOOST_AUTO_TEST_CASE(history_has_a_row_at_each_output_time_and_every_step_on_request) {
  // The sliding block: 1000 steps of 1 ms, outputs every 0.1 s.
  auto s = sliding(1.0, 0.1);
  const fs::path outputs = fresh_dir("rows-outputs");
  const auto r = run(s, outputs);
  BOOST_TEST_REQUIRE((r.status == scene::RunStatus::completed));
  const History h = read_history(outputs);
  BOOST_TEST_REQUIRE(h.rows.size() == 11u);  // t = 0, 0.1, ..., 1
  for (std::size_t k = 0; k < h.rows.size(); ++k) BOOST_TEST(near(h.at(k, "time"), 0.1 * double(k), 1.0));
  BOOST_TEST(h.at(10, "step") == 1000.0);

  s.analysis.history = scene::HistoryRows::steps;
  const fs::path steps = fresh_dir("rows-steps");
  BOOST_TEST_REQUIRE((run(s, steps).status == scene::RunStatus::completed));
  const History all = read_history(steps);
  BOOST_TEST(all.rows.size() == 1001u);
  // The same steps either way: the rows at the output times are the same rows.
  BOOST_TEST(all.rows.back() == h.rows.back(), boost::test_tools::per_element());
  BOOST_TEST(all.rows[500] == h.rows[5], boost::test_tools::per_element());
  // A hundredth of the bytes.
  BOOST_TEST(fs::file_size(outputs / "history.csv") * 50 < fs::file_size(steps / "history.csv"));
}

BOOST_AUTO_TEST_CASE(a_step_ends_on_every_output_time_under_an_adaptive_control) {
  // Frames used to come at the end of the first step past an output time (5.344,
  // 10.344 d for an interval of 5 d); now a step ends on each, and the step after it
  // takes up the size the control had reached (Engine::run_until).
  const fs::path one = fresh_dir("adaptive-one");
  const auto r1 = run(adaptive_creep(200.0), one);  // outputs at 0 and 200 h only
  BOOST_TEST_REQUIRE((r1.status == scene::RunStatus::completed));
  const fs::path many = fresh_dir("adaptive-many");
  const auto r = run(adaptive_creep(7.0), many);  // 7 h: no step size divides it
  BOOST_TEST_REQUIRE((r.status == scene::RunStatus::completed));
  std::vector<double> expected;
  for (int k = 0; k * 7.0 < 200.0; ++k) expected.push_back(7.0 * k);
  expected.push_back(200.0);
  const auto frames = frame_times(many);
  BOOST_TEST_REQUIRE(frames.size() == expected.size());
  for (std::size_t k = 0; k < frames.size(); ++k) BOOST_TEST(near(frames[k], expected[k], 200.0), frames[k]);
  const History h = read_history(many);
  BOOST_TEST_REQUIRE(h.rows.size() == expected.size());
  for (std::size_t k = 0; k < h.rows.size(); ++k) BOOST_TEST(near(h.at(k, "time"), expected[k], 200.0));
  // The landings cost about a step each, not a climb of the step size after each.
  BOOST_TEST(r.steps <= r1.steps + static_cast<int>(expected.size()) + 2, r.steps << " steps, " << r1.steps
                                                                                  << " with outputs at the end only");
  // And the answer is the control's: the displacement at 200 h agrees to the tolerance's order.
  const History h1 = read_history(one);
  BOOST_TEST(std::abs(h.at(h.rows.size() - 1, "A_joint.u") - h1.at(1, "A_joint.u")) < 1e-4);
}

BOOST_AUTO_TEST_CASE(output_times_add_rows_and_frames_where_asked) {
  auto s = sliding(1.0, 0.5);
  s.analysis.output_times = {0.123, 0.5, 0.777};
  const fs::path out = fresh_dir("output-times");
  BOOST_TEST_REQUIRE((run(s, out).status == scene::RunStatus::completed));
  const std::vector<double> expected{0.0, 0.123, 0.5, 0.777, 1.0};
  const auto frames = frame_times(out);
  BOOST_TEST_REQUIRE(frames.size() == expected.size());
  const History h = read_history(out);
  BOOST_TEST_REQUIRE(h.rows.size() == expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k) {
    BOOST_TEST(near(frames[k], expected[k], 1.0));
    BOOST_TEST(near(h.at(k, "time"), expected[k], 1.0));
  }
}

BOOST_AUTO_TEST_CASE(the_displacement_after_settling_counts_from_the_end_of_the_settling_stage) {
  const std::string text = settling_scene();
  const auto s = scene::parse_scene(text, "settling.yaml");
  const auto columns = scene::history_columns(s);
  const std::vector<std::string> point{"A_joint.u", "A_joint.v", "A_joint.u_after_settling", "A_joint.v_after_settling"};
  BOOST_TEST_REQUIRE((std::search(columns.begin(), columns.end(), point.begin(), point.end()) != columns.end()));
  // Without a settling stage the point's displacement counts from t = 0 already: no such columns.
  const auto plain = scene::history_columns(scene::parse_scene(kBaseScene, "plain.yaml"));
  BOOST_TEST((std::find(plain.begin(), plain.end(), "p.u_after_settling") == plain.end()));

  const fs::path dir = fresh_dir("after-settling");
  std::ofstream(dir / "scene.yaml") << text;
  const auto scene = scene::load_scene((dir / "scene.yaml").string());
  const fs::path out = dir / "out";
  BOOST_TEST_REQUIRE((run(scene, out).status == scene::RunStatus::completed));
  const History h = read_history(out);
  // Rows: t = 0, the settling stage's end (1 h), the output times 50 ... 200 h.
  BOOST_TEST_REQUIRE(h.rows.size() == 6u);
  BOOST_TEST(h.cell(0, "A_joint.u_after_settling").empty());  // before the stage's end
  BOOST_TEST(h.cell(0, "A_joint.v_after_settling").empty());
  BOOST_TEST(near(h.at(1, "time"), 1.0, 1.0));
  const double u0 = h.at(1, "A_joint.u"), v0 = h.at(1, "A_joint.v");
  BOOST_TEST(h.at(1, "A_joint.u_after_settling") == 0.0);
  BOOST_TEST(h.at(1, "A_joint.v_after_settling") == 0.0);
  BOOST_TEST(u0 > 0.005);  // the elastic shear of the joint under the load: settled
  for (std::size_t k = 2; k < h.rows.size(); ++k) {
    // The row's numbers are printed to 10 digits: the difference of the printed values, to that.
    BOOST_TEST(std::abs(h.at(k, "A_joint.u_after_settling") - (h.at(k, "A_joint.u") - u0)) <= 1e-9 * std::abs(u0));
    BOOST_TEST(std::abs(h.at(k, "A_joint.v_after_settling") - (h.at(k, "A_joint.v") - v0)) <= 1e-9 * std::abs(v0));
  }
  BOOST_TEST(h.at(5, "A_joint.u_after_settling") > 0.002);  // the creep after it: 2.4e-3 mm in 199 h

  // A resumed run takes the settled displacement up from its checkpoint: the same file.
  const fs::path part = dir / "part";
  BOOST_TEST_REQUIRE((run(scene, part, 15).status == scene::RunStatus::interrupted));  // after the settling's 10 steps
  BOOST_TEST_REQUIRE((run(scene, part, -1, true).status == scene::RunStatus::completed));
  BOOST_TEST(read_text((part / "history.csv").string()) == read_text((out / "history.csv").string()));

  // `rheodda plot` draws them in a panel of their own.
  scene::PlotOptions po;
  po.out_dir = out.string();
  (void)scene::plot_run(po);
  const std::string gp = read_text((out / "plots" / "history.gp").string());
  BOOST_TEST(gp.find("A_joint.u_after_settling") != std::string::npos);
  BOOST_TEST(gp.find("displacement after settling [mm]") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(frames_false_writes_the_history_and_the_summary_only) {
  const fs::path dir = fresh_dir("no-frames");
  auto s = sliding(1.0, 0.1);
  const fs::path earlier = dir / "out";
  BOOST_TEST_REQUIRE((run(s, earlier).status == scene::RunStatus::completed));  // an earlier run with frames
  BOOST_TEST(fs::exists(earlier / "blocks.pvd"));
  s.analysis.frames = false;
  const auto r = run(s, earlier);
  BOOST_TEST_REQUIRE((r.status == scene::RunStatus::completed));
  BOOST_TEST(r.frames == 0);
  for (const char* gone : {"contacts.csv", "blocks.pvd", "contacts.pvd", "frames"})
    BOOST_TEST(!fs::exists(earlier / gone), gone << " of the earlier run is left");
  BOOST_TEST(read_history(earlier).rows.size() == 11u);
  BOOST_TEST(nlohmann::json::parse(read_text((earlier / "summary.json").string())).at("frames") == 0);
  // Stopped and resumed: the same history.
  const fs::path part = dir / "part";
  BOOST_TEST_REQUIRE((run(s, part, 444).status == scene::RunStatus::interrupted));
  BOOST_TEST_REQUIRE((run(s, part, -1, true).status == scene::RunStatus::completed));
  BOOST_TEST(read_text((part / "history.csv").string()) == read_text((earlier / "history.csv").string()));
  // `rheodda plot` draws the history and says why there are no blocks.
  std::vector<std::string> warnings;
  scene::PlotOptions po;
  po.out_dir = earlier.string();
  po.warn = [&](const std::string& w) { warnings.push_back(w); };
  const auto pictures = scene::plot_run(po);
  BOOST_TEST_REQUIRE(pictures.size() == 1u);
  BOOST_TEST(pictures[0].find("history.png") != std::string::npos);
  BOOST_TEST_REQUIRE(warnings.size() == 1u);
  BOOST_TEST(warnings[0].find("no frames (analysis.frames: false)") != std::string::npos);
}

BOOST_AUTO_TEST_SUITE_END()
