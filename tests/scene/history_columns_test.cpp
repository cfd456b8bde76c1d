// history.csv's columns (scene/history_columns.hpp), declared once: a run's header is the
// declared columns of the scene's parts in order; every declared column has its unit on
// the plots' axes; `rheodda keys history` prints them; and docs/reference/outputs.md's
// table is the declarations'.
#include <boost/test/unit_test.hpp>

#include <set>

#include "declared_key_checks.hpp"
#include "test_support.hpp"
#include "rheodda/scene/history_columns.hpp"
#include "rheodda/scene/loader.hpp"
#include "rheodda/scene/output.hpp"
#include "rheodda/scene/plot.hpp"

using namespace rheodda;
using namespace rheodda::test;

BOOST_AUTO_TEST_SUITE(history_columns)

BOOST_AUTO_TEST_CASE(a_runs_header_is_the_declared_columns_of_its_parts) {
  // kBaseScene has the point `p`; with `record: true` on `bedding` and a settling stage.
  const scene::SceneDescription s = scene::parse_scene(
      with("  bedding: {friction_angle: 30}", "  bedding: {friction_angle: 30, record: true}",
           with("  dt: 0.01", "  dt: 0.01\n  settle: {until: 0.1, dt: 0.01}")),
      "columns.yaml");
  const std::vector<std::string> header = scene::history_columns(s);
  std::vector<std::string> expected;
  for (const scene::HistoryColumns& c : scene::history_column_specs()) {
    if (c.part == scene::HistoryPart::bolt || c.part == scene::HistoryPart::stage) continue;  // none in this scene
    const std::string owner = c.part == scene::HistoryPart::point || c.part == scene::HistoryPart::point_settled ? "p"
                              : c.part == scene::HistoryPart::joint_set                                        ? "bedding"
                                                                                                               : "";
    for (const std::string& n : c.names) expected.push_back(owner + n);
  }
  // The point's columns after settling follow its own (one point here: the declared order).
  BOOST_TEST(header == expected, boost::test_tools::per_element());
  // The energy balance is kHistoryEnergyColumns, the values history_energy_values gives.
  const std::vector<std::string> energy = scene::history_part_columns(scene::HistoryPart::energy);
  BOOST_TEST(energy == std::vector<std::string>(scene::kHistoryEnergyColumns.begin(), scene::kHistoryEnergyColumns.end()),
             boost::test_tools::per_element());
}

BOOST_AUTO_TEST_CASE(every_declared_column_has_its_unit_on_the_plots) {
  for (const scene::HistoryColumns& c : scene::history_column_specs())
    for (const std::string& n : c.names) {
      const std::string column = n.front() == '.' ? "x" + n : n;
      const std::string unit = scene::history_column_unit(column, "m", "N", "s");
      BOOST_TEST(!unit.empty(), column);
      if (c.unit == "length") BOOST_TEST(unit == "m", column);
      if (c.unit == "time") BOOST_TEST(unit == "s", column);
      if (c.unit == "–") BOOST_TEST(unit == "-", column);
    }
}

BOOST_AUTO_TEST_CASE(rheodda_keys_prints_them_and_the_docs_table_is_the_declarations) {
  const CommandResult r = run_rheodda("keys history");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.output);
  for (const scene::HistoryColumns& c : scene::history_column_specs())
    for (const std::string& n : c.names) {
      const std::string line = "history." + n + " [" + c.unit + "]: " + c.meaning + "\n";
      BOOST_TEST(r.output.find(line) != std::string::npos, "no line " << line);
    }
  check_doc_table("docs/reference/outputs.md", "history", scene::history_table_markdown());
}

BOOST_AUTO_TEST_SUITE_END()
