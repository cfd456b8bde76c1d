// The seed's toppling study (section 5), reduced: the Goodman slope of
// examples/goodman-toppling.yaml run through `rheodda study` over a few days
// instead of 100, reproduces the seed's trends (docs/toppling-study.md):
// without creep, the slope slides far when the base friction angle is low, less
// as it grows, and only settles elastically when it is high; with creep at phi = 50 deg the displacement of
// blocks 1 and 10 grows with time.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <string>

#include "study_support.hpp"

using namespace rheodda::study_test;
namespace fs = std::filesystem;

BOOST_AUTO_TEST_SUITE(toppling_trend)

BOOST_AUTO_TEST_CASE(reduced_toppling_study_displacement_falls_with_phi_and_creep_grows_with_time) {
  const fs::path dir = fresh_dir("toppling");
  const std::string scene = source_path("examples/goodman-toppling.yaml");

  // Without creep (the laws removed, the joints keep E1 = 1e8 Pa/m as elastic shear stiffness).
  const fs::path phi = dir / "phi.yaml";
  std::ofstream(phi) << "scene: " << scene << "\n"
                     << "set:\n"
                        "  joint_sets.base.law: ~\n"
                        "  joint_sets.base.shear_stiffness: 1.0e8\n"
                        "  joint_sets.anti_toppling.law: ~\n"
                        "  joint_sets.anti_toppling.shear_stiffness: 1.0e8\n"
                        "  analysis.duration: 2\n"
                        "  analysis.max_displacement_ratio: 0.0005\n"
                        "outputs: [block1_top.displacement, block10_top.displacement]\n"
                        "times: [2]\n"
                        "cases:\n"
                        "  - {name: phi33, set: {joint_sets.base.friction_angle: 33}}\n"
                        "  - {name: phi35, set: {joint_sets.base.friction_angle: 35}}\n"
                        "  - {name: phi45, set: {joint_sets.base.friction_angle: 45}}\n"
                        "  - {name: phi55, set: {joint_sets.base.friction_angle: 55}}\n";
  const auto r = run_rheodda("study " + phi.string() + " -o " + (dir / "phi").string() + " -j 2 --no-plot");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.output);
  const auto rows = read_study_csv((dir / "phi" / "study.csv").string());
  BOOST_TEST_REQUIRE(rows.size() == 4u);
  const auto d = [&](std::size_t i, const std::string& col) { return std::stod(rows[i].at(col + "@2")); };
  for (const std::string col : {"block1_top.displacement", "block10_top.displacement"}) {
    BOOST_TEST_CONTEXT(col) {
      // phi = 33 deg: the slope slides along its base (metres); the displacement falls as
      // phi grows (35 deg) to the columns' settling alone, the same within 30% at 45 and 55 deg.
      BOOST_TEST(d(0, col) > 2.0);
      BOOST_TEST(d(0, col) > 10.0 * d(1, col));
      BOOST_TEST(d(1, col) > d(2, col));
      BOOST_TEST(std::abs(d(3, col) - d(2, col)) < 0.3 * d(2, col));
    }
  }

  // With the seed's Table 3 Burgers joints at phi = 50 deg (the example as shipped, g2 = 0.0005), 20 days.
  const fs::path creep = dir / "creep.yaml";
  std::ofstream(creep) << "scene: " << scene << "\n"
                       << "set: {analysis.duration: 20, analysis.max_displacement_ratio: 0.0005}\n"
                          "outputs: [block1_top.displacement, block10_top.displacement]\n"
                          "times: [1, 5, 10, 20]\n"
                          "cases:\n"
                          "  - {name: phi50}\n";
  const auto c = run_rheodda("study " + creep.string() + " -o " + (dir / "creep").string() + " --no-plot");
  BOOST_TEST_REQUIRE(c.exit_code == 0, c.output);
  const auto crow = read_study_csv((dir / "creep" / "study.csv").string());
  BOOST_TEST_REQUIRE(crow.size() == 1u);
  for (const std::string col : {"block1_top.displacement", "block10_top.displacement"}) {
    BOOST_TEST_CONTEXT(col) {
      const double d1 = std::stod(crow[0].at(col + "@1")), d5 = std::stod(crow[0].at(col + "@5"));
      const double d10 = std::stod(crow[0].at(col + "@10")), d20 = std::stod(crow[0].at(col + "@20"));
      BOOST_TEST(d5 > d1);
      BOOST_TEST(d10 > d5);
      BOOST_TEST(d20 > d10);
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()
