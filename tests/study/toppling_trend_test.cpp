// The seed's toppling study (section 5), reduced: the Goodman slope of
// bench/scenes/goodman-toppling-seed-steps.yaml (the seed's slope on its own static
// steps, which each case here refines) run through `rheodda study` over a few days
// instead of 100, reproduces the seed's trends (docs/guide/toppling-study.md):
// without creep, the slope slides far along its base when the base friction
// angle is low and stands on a plateau above it, where the columns' settling
// falls gently as phi grows; with creep at phi = 50 deg the displacement of
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
  const std::string scene = source_path("bench/scenes/goodman-toppling-seed-steps.yaml");

  // Without creep (the laws removed, the joints keep E1 = 1e8 Pa/m as elastic shear stiffness),
  // on step controls the refinement study justifies: max_displacement_ratio 6.25e-5 with dt 1/32 d is
  // level L4 of scripts/refinement-goodman.sh (docs/reference/contacts.md), where block 10
  // agrees with level L3 within 2 % at 35 and 55 deg and 6 % at 45 deg; the
  // shipped max_displacement_ratio 0.0005 with dt 0.5 d is not converged (block 1 at 45 deg: 0.094 m
  // there, 0.062 m at L4).
  const fs::path phi = dir / "phi.yaml";
  std::ofstream(phi) << "scene: " << scene << "\n"
                     << "set:\n"
                        "  joint_sets.base.law: ~\n"
                        "  joint_sets.base.shear_stiffness: 1.0e8\n"
                        "  joint_sets.anti_toppling.law: ~\n"
                        "  joint_sets.anti_toppling.shear_stiffness: 1.0e8\n"
                        "  analysis.duration: 2\n"
                        "  analysis.max_displacement_ratio: 6.25e-5\n"
                        "  analysis.dt: 0.03125\n"
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
      // phi = 33 deg: the slope slides along its base (metres, 7.3 and 27 m at L4).
      // From 35 deg on it stands: a plateau (35, 45 and 55 deg within 30 % of
      // 45 deg; at L4 they are 16 % and 2 % apart for block 1, 11 % and 6 % for
      // block 10) on which the displacement falls from 35 to 55 deg (by 13-18 % at
      // L3 and L4, where the two levels differ by 0.1-2 % at 35 and 55 deg).
      BOOST_TEST(d(0, col) > 2.0);
      BOOST_TEST(d(0, col) > 10.0 * d(1, col));
      BOOST_TEST(std::abs(d(1, col) - d(2, col)) < 0.3 * d(2, col));
      BOOST_TEST(std::abs(d(3, col) - d(2, col)) < 0.3 * d(2, col));
      BOOST_TEST(d(1, col) > d(3, col));
    }
  }

  // With the seed's Table 3 Burgers joints at phi = 50 deg, 20 days, on levels L3
  // (max_displacement_ratio 1.25e-4, dt 1/16 d) and L2 (2.5e-4, 1/8 d) of the same refinement
  // (scripts/refinement-goodman-creep.sh, docs/notes/step-controls.md "The seed's
  // slope itself, refined": levels L2-L4 lie within 5 % of each other at 10 and
  // 20 d, L3 and L4 up to 4.9 % apart). (Coarser controls do not show the
  // trend: at max_displacement_ratio 0.01, dt 0.5 d block 1 is at 0.73 m at 5 d and 0.19 m at 10 d.)
  const fs::path creep = dir / "creep.yaml";
  std::ofstream(creep) << "scene: " << scene << "\n"
                       << "set: {analysis.duration: 20, analysis.max_displacement_ratio: 1.25e-4, analysis.dt: 0.0625}\n"
                          "outputs: [block1_top.displacement, block10_top.displacement]\n"
                          "times: [1, 5, 10, 20]\n"
                          "cases:\n"
                          "  - {name: phi50}\n"
                          "  - {name: phi50_L2, set: {analysis.max_displacement_ratio: 2.5e-4, analysis.dt: 0.125}}\n";
  const auto c = run_rheodda("study " + creep.string() + " -o " + (dir / "creep").string() + " --no-plot");
  BOOST_TEST_REQUIRE(c.exit_code == 0, c.output);
  const auto crow = read_study_csv((dir / "creep" / "study.csv").string());
  BOOST_TEST_REQUIRE(crow.size() == 2u);
  for (const std::string col : {"block1_top.displacement", "block10_top.displacement"}) {
    for (std::size_t k = 0; k < crow.size(); ++k) {
      BOOST_TEST_CONTEXT(crow[k].at("case") << " " << col) {
        const double d1 = std::stod(crow[k].at(col + "@1")), d5 = std::stod(crow[k].at(col + "@5"));
        const double d10 = std::stod(crow[k].at(col + "@10")), d20 = std::stod(crow[k].at(col + "@20"));
        BOOST_TEST(d5 > d1);
        BOOST_TEST(d10 > d5);
        BOOST_TEST(d20 > d10);
      }
    }
    // The two refinement levels agree within the spread the placement of the steps gives
    // at these levels: a step ends on each output time, and outputs every 0.5, 1 or 2 d
    // put block 1 at 10 d at 0.68-0.73 m on L3 and 0.73-0.79 m on L2 (up to 8 % on a
    // level, 16 % across the two), block 10 at 4.71-4.98 and 4.99-5.30 m
    // (docs/notes/step-controls.md, "Output times and the steps"; with frames after the
    // first step past each output time the levels were 1-2 % apart). Here, outputs
    // every 1 d, they are 10 % apart at 10 d.
    for (const std::string t : {"@10", "@20"}) {
      const double l3 = std::stod(crow[0].at(col + t)), l2 = std::stod(crow[1].at(col + t));
      BOOST_TEST(std::abs(l2 - l3) < 0.15 * l3, col << t << ": L2 " << l2 << ", L3 " << l3);
    }
  }
}

BOOST_AUTO_TEST_CASE(seed_slope_settled_dynamically_is_the_same_at_two_steps) {
  // The phi sweep of docs/guide/toppling-study.md (examples/studies/toppling-phi.yaml):
  // no creep, gravity at t = 0, dynamic with plastic impacts and damped blocks,
  // 20 s. Levels L1 and L2 of `scripts/refinement-goodman.sh --dynamic` (dt 1 and
  // 0.5 ms, max_displacement_ratio halved with it): block 10 settles at 1.979 and 1.978 m at 45 deg,
  // and every level from 2 ms down lies within 0.05 % of the next
  // (docs/notes/contact-solves.md, "The same slope settled dynamically"). Before the
  // slide-reversal fix ("Friction that pushed") the 0.5 ms run never came to
  // rest; before the joint's springs took the tributary length on point
  // contacts too ("Springs of a joint on point contacts") the settled state
  // changed with max_displacement_ratio through the contact search distance. At 33 deg the slope
  // slides along its base.
  const fs::path dir = fresh_dir("toppling_dynamic");
  const std::string scene = source_path("bench/scenes/goodman-toppling-seed-steps.yaml");
  const fs::path yaml = dir / "dyn.yaml";
  std::ofstream(yaml) << "scene: " << scene << "\n"
                      << "set:\n"
                         "  joint_sets.base.law: ~\n"
                         "  joint_sets.base.shear_stiffness: 1.0e8\n"
                         "  joint_sets.base.restitution: 0\n"
                         "  joint_sets.anti_toppling.law: ~\n"
                         "  joint_sets.anti_toppling.shear_stiffness: 1.0e8\n"
                         "  joint_sets.anti_toppling.restitution: 0\n"
                         "  materials.rock.damping_ratio: 1\n"
                         "  analysis.type: dynamic\n"
                         "  analysis.scheme: ~\n"
                         "  analysis.duration: 2.3148148e-4\n"       // d (20 s)
                         "  analysis.output_interval: 1.1574074e-4\n"  // d (10 s)
                         "outputs: [block10_top.displacement]\n"
                         "times: [1.1574074e-4, 2.3148148e-4]\n"
                         "cases:\n"
                         "  - {name: phi45_L1, set: {joint_sets.base.friction_angle: 45, analysis.dt: 1.1574074e-8,"
                         " analysis.max_displacement_ratio: 0.0005}}\n"
                         "  - {name: phi45_L2, set: {joint_sets.base.friction_angle: 45, analysis.dt: 5.787037e-9,"
                         " analysis.max_displacement_ratio: 0.00025}}\n"
                         "  - {name: phi33_L2, set: {joint_sets.base.friction_angle: 33, analysis.dt: 5.787037e-9,"
                         " analysis.max_displacement_ratio: 0.00025}}\n";
  const auto r = run_rheodda("study " + yaml.string() + " -o " + (dir / "out").string() + " -j 2 --no-plot");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.output);
  const auto rows = read_study_csv((dir / "out" / "study.csv").string());
  BOOST_TEST_REQUIRE(rows.size() == 3u);
  // The columns name the times as given (%g would round them to 0.000231481: issue 52).
  const auto d = [&](std::size_t i, const char* t) {
    return std::stod(rows[i].at(std::string("block10_top.displacement@") + t));
  };
  const double l1 = d(0, "0.00023148148"), l2 = d(1, "0.00023148148");
  BOOST_TEST_MESSAGE("block 10 at 20 s: L1 " << l1 << " m, L2 " << l2 << " m; phi 33 deg " << d(2, "0.00023148148")
                                              << " m");
  BOOST_TEST(l1 > 1.0);                                   // the columns collapse onto each other
  BOOST_TEST(std::abs(l1 - l2) < 0.005 * l2);             // the two levels agree
  for (std::size_t i = 0; i < 2; ++i)                     // at rest: the same at 10 s and 20 s
    BOOST_TEST(std::abs(d(i, "0.00011574074") - d(i, "0.00023148148")) < 1e-6 * d(i, "0.00023148148"));
  BOOST_TEST(d(2, "0.00023148148") > 10.0 * l2);            // 33 deg: the slope slides
}

BOOST_AUTO_TEST_SUITE_END()
