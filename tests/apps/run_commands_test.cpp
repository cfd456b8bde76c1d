// The rheodda command on scenes: `check` prints what will be modelled, bad input
// exits 2 with file:line:column and writes nothing, `plot` draws pictures.
#include <boost/test/unit_test.hpp>

#include "rheodda/scene/plot.hpp"
#include "rheodda/scene/progress.hpp"
#include "../scene/test_support.hpp"

using namespace rheodda::test;
namespace fs = std::filesystem;

BOOST_AUTO_TEST_SUITE(scene_commands)

BOOST_AUTO_TEST_CASE(check_accepts_every_shipped_example) {
  for (const char* name : {"shear-creep-test.yaml", "goodman-toppling.yaml", "sliding-block.yaml"}) {
    const auto r = run_rheodda("check " + source_path(std::string("examples/") + name));
    BOOST_TEST(r.exit_code == 0, name << ":\n" << r.output);
    BOOST_TEST(r.output.find("scene OK") != std::string::npos);
  }
}

BOOST_AUTO_TEST_CASE(check_prints_blocks_joint_sets_laws_and_estimated_contacts) {
  const auto r = run_rheodda("check " + source_path("examples/goodman-toppling.yaml"));
  BOOST_TEST(r.exit_code == 0);
  const std::string& o = r.output;
  BOOST_TEST(o.find("units: length m, force N, time d") != std::string::npos);
  BOOST_TEST(o.find("blocks (17)") != std::string::npos);
  BOOST_TEST(o.find("base: friction_angle 50 deg") != std::string::npos);
  BOOST_TEST(o.find("law burgers: E1=1e+08 E2=2.5e+08 eta1=2e+08 eta2=6.2e+09") != std::string::npos);
  BOOST_TEST(o.find("anti_toppling: friction_angle 25 deg") != std::string::npos);
  // 16 columns on the base and 15 column-column joints, each face to face: 2 contacts.
  BOOST_TEST(o.find("estimated contacts at the start: 62 between 31 block pairs") != std::string::npos, o);
  BOOST_TEST(o.find("block10_top") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(check_of_an_explicit_scene_prints_the_spread_of_the_blocks_cycles) {
  // The sliding block on its incline: one block moves, so it sets the scene's cycle and the
  // spread's every figure, and it is the shortest.
  const fs::path dir = fresh_dir("cycles");
  const fs::path scene = dir / "explicit.yaml";
  std::ofstream(scene) << with("  type: dynamic\n", "  type: dynamic\n  integrator: explicit\n",
                               read_text(source_path("examples/sliding-block.yaml")));
  const auto r = run_rheodda("check " + scene.string());
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.output);
  const std::string& o = r.output;
  const auto at = o.find("the blocks' cycles (1 blocks): smallest ");
  BOOST_TEST_REQUIRE(at != std::string::npos, o);
  const auto set_by = o.find("set by block 'block'");
  BOOST_TEST(set_by != std::string::npos, o);
  BOOST_TEST(o.find("the shortest: 'block' (", at) != std::string::npos, o);
  BOOST_TEST(o.find("area 0.5 m^2)", at) != std::string::npos, o);
}

BOOST_AUTO_TEST_CASE(bad_scene_exits_2_with_file_line_column_and_writes_nothing) {
  const fs::path dir = fresh_dir("bad");
  const fs::path file = dir / "bad.yaml";
  std::ofstream(file) << with("  dt: 0.01", "  dt: -0.01");
  const auto c = run_rheodda("check " + file.string());
  BOOST_TEST(c.exit_code == 2);
  BOOST_TEST(c.output.find(file.string() + ":4:7: analysis.dt: -0.01 is out of range") != std::string::npos, c.output);
  const auto r = run_rheodda("run " + file.string() + " -o " + (dir / "out").string());
  BOOST_TEST(r.exit_code == 2);
  BOOST_TEST(!fs::exists(dir / "out"));
  BOOST_TEST(run_rheodda("check " + (dir / "missing.yaml").string()).exit_code == 2);
}

BOOST_AUTO_TEST_CASE(run_prints_plain_lines_off_a_terminal_and_plot_draws_block_pictures_and_history_curves) {
  const fs::path dir = fresh_dir("plot");
  const fs::path scene = dir / "short.yaml";
  std::ofstream(scene) << with("  duration: 1 ", "  duration: 0.1 ",
                               read_text(source_path("examples/sliding-block.yaml")));
  const auto r = run_rheodda("run " + scene.string() + " -o " + (dir / "out").string());
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.output);
  // Not a terminal: no redrawn line, a plain line at the start and at the end (a run shorter than
  // 10 s: none between; docs/reference/cli.md, "Progress"), and the summary.
  BOOST_TEST(r.output.find('\r') == std::string::npos);
  BOOST_TEST(r.output.find("rheodda run: start, dynamic, t = 0 of 0.1 s (0.0 %), step 0") != std::string::npos, r.output);
  BOOST_TEST(r.output.find("rheodda run: completed, dynamic, t = 0.1 of 0.1 s (100.0 %), step 100") != std::string::npos,
             r.output);
  BOOST_TEST(r.output.find("completed at t = 0.1 of 0.1 s: 100 steps") != std::string::npos, r.output);
  const auto p = run_rheodda("plot " + (dir / "out").string() + " --times 0,0.1");
  BOOST_TEST_REQUIRE(p.exit_code == 0, p.output);
  for (const char* f : {"plots/blocks_000000.png", "plots/blocks_000005.png", "plots/history.png"}) {
    const std::string png = read_text((dir / "out" / f).string());
    BOOST_TEST(png.substr(0, 4) == "\x89PNG", f);
  }
  BOOST_TEST(run_rheodda("plot " + (dir / "nothing").string()).exit_code == 2);
  // Times with their units, converted into the run's (s): 60 ms is frame 3 of 0, 0.02, ... 0.1 s.
  const auto u = run_rheodda("plot " + (dir / "out").string() + " --times '60 ms' --from '20 ms' --to '0.08 s'");
  BOOST_TEST_REQUIRE(u.exit_code == 0, u.output);
  BOOST_TEST(u.output.find("plots/blocks_000003.png") != std::string::npos, u.output);
  BOOST_TEST(u.output.find("plots/contacts_000003.png") != std::string::npos, u.output);
  BOOST_TEST(read_text((dir / "out" / "plots" / "history.gp").string()).find("set xrange [0.02:0.080000000000000002]") != std::string::npos);
  const auto wrong = run_rheodda("plot " + (dir / "out").string() + " --from '5 m'");
  BOOST_TEST(wrong.exit_code == 2);
  BOOST_TEST(wrong.output.find("--from: '5 m' has the wrong dimension: m is length, this key takes time") !=
             std::string::npos, wrong.output);
}

BOOST_AUTO_TEST_CASE(the_time_left_is_that_of_the_recent_rate_and_reads_as_minutes_and_hours) {
  using rheodda::scene::RateEstimate;
  RateEstimate r(60.0);
  BOOST_TEST(!r.seconds_left(0.0, 100.0).has_value());  // nothing measured yet
  r.add(0.0, 0.0);
  r.add(1.0, 1.0);
  BOOST_TEST(!r.seconds_left(1.0, 100.0).has_value());  // less than 2 s of it
  // 1 unit a second for 100 s, then 4 a second: the window (the last minute) sees mostly the new rate.
  for (int k = 2; k <= 100; ++k) r.add(k, k);
  BOOST_TEST(*r.seconds_left(100.0, 160.0) == 60.0, boost::test_tools::tolerance(1e-12));
  for (int k = 1; k <= 60; ++k) r.add(100.0 + k, 100.0 + 4.0 * k);
  BOOST_TEST(r.span() <= 61.0);
  BOOST_TEST(*r.seconds_left(340.0, 740.0) == 100.0, boost::test_tools::tolerance(0.02));
  r.add(160.2, 1000.0);  // within half a second of the last sample: not kept
  BOOST_TEST(*r.seconds_left(340.0, 740.0) == 100.0, boost::test_tools::tolerance(0.02));
  r.reset();  // a new stage
  BOOST_TEST(!r.seconds_left(340.0, 740.0).has_value());
  BOOST_TEST(rheodda::scene::duration_text(42.4) == "42 s");
  BOOST_TEST(rheodda::scene::duration_text(190) == "3 min 10 s");
  BOOST_TEST(rheodda::scene::duration_text(2 * 3600 + 5 * 60 + 10) == "2 h 05 min");
}

BOOST_AUTO_TEST_CASE(a_long_picture_title_is_broken_into_lines_that_fit_and_keeps_every_word) {
  // A study case's title lists every setting it changes; it ran off the picture.
  std::string title = "Goodman slope [case phi33: joint_sets.base.friction_angle = 33";
  for (int k = 0; k < 12; ++k) title += ", joint_sets.set" + std::to_string(k) + ".law removed";
  title += ", a \"quoted\" C:\\path]";
  const std::string q = rheodda::scene::gnuplot_wrapped(title, 110);
  BOOST_TEST_REQUIRE(q.size() > 2);
  BOOST_TEST(q.front() == '"');
  BOOST_TEST(q.back() == '"');
  // Undo the gnuplot escapes: \n ends a line, \" and \\ stand for " and \.
  std::vector<std::string> lines(1);
  for (std::size_t i = 1; i + 1 < q.size(); ++i) {
    if (q[i] == '\\') {
      const char next = q[++i];
      if (next == 'n') lines.emplace_back();
      else lines.back() += next;
    } else {
      lines.back() += q[i];
    }
  }
  BOOST_TEST(lines.size() >= 4u);
  std::string joined;
  for (const auto& l : lines) {
    BOOST_TEST(l.size() <= 110u, l);
    BOOST_TEST(!l.empty());
    joined += (joined.empty() ? "" : " ") + l;
  }
  BOOST_TEST(joined == title);
  // A short title stays on one line.
  BOOST_TEST(rheodda::scene::gnuplot_wrapped("shear creep test", 110) == "\"shear creep test\"");
}

BOOST_AUTO_TEST_SUITE_END()
