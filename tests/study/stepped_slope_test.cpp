// A slope that limit equilibrium holds with a margin of 5 deg stands at every
// step, dynamic and static (issue "Steps that converge", docs/notes/contact-solves.md
// "Stick and slip"): bench/scenes/stepped-toppling.yaml, the Goodman & Bray
// toppling slope on its stepped base at friction 43.15 deg (limit equilibrium:
// 38.15 deg, tests/contact/engine/toppling_test.cpp), with the scene's default
// contact settings, run through `rheodda study` for 2 s at dt = 5 ms to 0.1 ms.
// The same slope 5 deg below its limit (33.15 deg) topples: the threshold
// separates a slope that stands (settling of millimetres) from one that moves.
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "study_support.hpp"

using namespace rheodda::study_test;
namespace fs = std::filesystem;

namespace {

/// The study's `outputs:` line: the displacement of the 16 block tops.
std::string tops_outputs() {
  std::string outputs = "outputs: [";
  for (int b = 1; b <= 16; ++b) outputs += "b" + std::to_string(b) + "_top.displacement" + (b < 16 ? ", " : "]\n");
  return outputs;
}

/// The largest displacement of the 16 block tops at 2 s in a study.csv row [m].
double largest_top(const std::map<std::string, std::string>& row) {
  double m = 0.0;
  for (int b = 1; b <= 16; ++b) m = std::max(m, std::stod(row.at("b" + std::to_string(b) + "_top.displacement@2")));
  return m;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(stepped_slope)

BOOST_AUTO_TEST_CASE(a_slope_5_deg_above_limit_equilibrium_stands_at_every_step_dynamic_and_static) {
  const fs::path dir = fresh_dir("stepped");
  const std::string outputs = tops_outputs();
  const fs::path study = dir / "study.yaml";
  std::ofstream(study) << "scene: " << source_path("bench/scenes/stepped-toppling.yaml") << "\n"
                       << "set: {analysis.duration: 2, analysis.output_interval: 1}\n"
                       << outputs << "times: [2]\n"
                       << "cases:\n"
                          "  - {name: dynamic_5ms, set: {analysis.dt: 0.005}}\n"
                          "  - {name: dynamic_1ms, set: {analysis.dt: 0.001}}\n"
                          "  - {name: dynamic_0.25ms, set: {analysis.dt: 0.00025}}\n"
                          "  - {name: dynamic_0.1ms, set: {analysis.dt: 0.0001}}\n"
                          "  - {name: static_10ms, set: {analysis.type: static, analysis.dt: 0.01}}\n"
                          "  - {name: static_0.1ms, set: {analysis.type: static, analysis.dt: 0.0001}}\n"
                          "  - {name: below_limit, set: {analysis.dt: 0.005, joint_sets.joint.friction_angle: 33.15}}\n";
  const auto r = run_rheodda("study " + study.string() + " -o " + (dir / "out").string() + " -j 2 --no-plot");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.output);
  const auto rows = read_study_csv((dir / "out" / "study.csv").string());
  BOOST_TEST_REQUIRE(rows.size() == 7u);
  for (const auto& row : rows) {
    BOOST_TEST_CONTEXT(row.at("case")) {
      BOOST_TEST(row.at("status") == "completed");
      const double largest = largest_top(row);
      // Standing: settling of 1-14 mm (docs/reference/contacts.md); toppling: metres.
      if (row.at("case") == "below_limit")
        BOOST_TEST(largest > 0.5);
      else
        BOOST_TEST(largest < 0.05);
      // study.csv's inertia_share is the case's summary.json static_mechanism
      // share: empty for a dynamic case. The static cases settle by rotating
      // their columns, which a static step holds by its inertia term alone
      // (docs/reference/engine.md, "Mechanisms in static analysis": 0.39 at 10 ms, 0.67 at
      // 0.1 ms, and 4.5 against 1.2 mm of settling), so they are flagged.
      const auto summary = nlohmann::json::parse(
          read_text((dir / "out" / "cases" / row.at("case") / "summary.json").string()));
      if (row.at("case").rfind("static", 0) == 0) {
        BOOST_TEST_REQUIRE(!row.at("inertia_share").empty());
        BOOST_TEST(std::stod(row.at("inertia_share")) ==
                   summary.at("static_mechanism").at("inertia_share").get<double>());
        BOOST_TEST(std::stod(row.at("inertia_share")) > 0.01);
      } else {
        BOOST_TEST(row.at("inertia_share").empty());
        BOOST_TEST(summary.at("static_mechanism").is_null());
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(with_plastic_impacts_and_damped_blocks_the_settling_does_not_depend_on_the_step) {
  // Joint set restitution 0, material damping_ratio 1 (docs/reference/contacts.md, "Contact
  // damping", and docs/notes/contact-solves.md, "Stick and slip"): 6.1-6.4 mm at 8 s from 5 ms to 0.05 ms, where
  // the undamped default settles 7.7-14.3 mm, more at every smaller step.
  const fs::path dir = fresh_dir("stepped-damped");
  const std::string outputs = tops_outputs();
  const fs::path study = dir / "study.yaml";
  std::ofstream(study) << "scene: " << source_path("bench/scenes/stepped-toppling.yaml") << "\n"
                       << "set: {analysis.duration: 2, analysis.output_interval: 1, joint_sets.joint.restitution: 0, "
                          "materials.rock.damping_ratio: 1}\n"
                       << outputs << "times: [2]\n"
                       << "cases:\n"
                          "  - {name: dt5ms, set: {analysis.dt: 0.005}}\n"
                          "  - {name: dt1ms, set: {analysis.dt: 0.001}}\n"
                          "  - {name: dt0.25ms, set: {analysis.dt: 0.00025}}\n"
                          "  - {name: dt0.1ms, set: {analysis.dt: 0.0001}}\n";
  const auto r = run_rheodda("study " + study.string() + " -o " + (dir / "out").string() + " -j 2 --no-plot");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.output);
  const auto rows = read_study_csv((dir / "out" / "study.csv").string());
  BOOST_TEST_REQUIRE(rows.size() == 4u);
  std::vector<double> largest;  // per case, the largest displacement of the 16 block tops at 2 s [m]
  for (const auto& row : rows) {
    BOOST_TEST(row.at("status") == "completed");
    const double m = largest_top(row);
    BOOST_TEST_MESSAGE("damped, " << row.at("case") << ": largest displacement " << m * 1e3 << " mm");
    largest.push_back(m);
  }
  // It stands (millimetres), and every step gives the finest step's settling within 10 %.
  for (const double m : largest) {
    BOOST_TEST(m < 0.01);
    BOOST_TEST(m == largest.back(), boost::test_tools::tolerance(0.1));
  }
}

BOOST_AUTO_TEST_SUITE_END()
