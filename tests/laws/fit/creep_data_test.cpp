// Reading creep curves from CSV: stages from a stress column or from --stress,
// and every kind of bad data rejected with the file, line and column.
#include <boost/test/unit_test.hpp>

#include <sstream>
#include <utility>
#include <vector>

#include "rheodda/fit/creep_data.hpp"

namespace {

using namespace rheodda;

fit::CreepData parse(const std::string& text, fit::CsvOptions o) {
  std::istringstream in(text);
  return fit::parse_creep_csv(in, "lab.csv", o);
}

fit::CsvOptions with_stress(double v) {
  fit::CsvOptions o;
  o.stress = laws::StagedHistory({{0.0, v}});
  return o;
}

fit::CsvOptions with_column(const std::string& c) {
  fit::CsvOptions o;
  o.stress_column = c;
  return o;
}

// Checks that parsing throws a DataError at `line` naming `column`.
void expect_error(const std::string& text, const fit::CsvOptions& o, std::size_t line,
                  const std::string& column, const std::string& words) {
  try {
    parse(text, o);
    BOOST_ERROR("no error for: " << text);
  } catch (const fit::DataError& e) {
    BOOST_TEST(e.file() == "lab.csv");
    BOOST_TEST(e.line() == line);
    BOOST_TEST(e.column() == column);
    const std::string what = e.what();
    BOOST_TEST(what.find(words) != std::string::npos, what);
    BOOST_TEST(what.find("lab.csv") == 0u, what);
  }
}

}  // namespace

BOOST_AUTO_TEST_SUITE(creep_data)

BOOST_AUTO_TEST_CASE(single_stress_file_gives_one_stage_with_every_row) {
  const auto d = parse("# creep test\nt,displacement\n0,0.0086\n1,0.0090\n\n2,0.0093\n", with_stress(0.232));
  BOOST_TEST(d.t.size() == 3u);
  BOOST_TEST(d.stages.size() == 1u);
  BOOST_TEST(d.stages[0].count == 3u);
  BOOST_TEST(d.stages[0].stress == 0.232);
  BOOST_TEST(d.line[2] == 6u);  // comments and blank lines still count as file lines
}

BOOST_AUTO_TEST_CASE(byte_order_mark_and_spaces_around_cells_are_accepted) {
  const auto d = parse("\xEF\xBB\xBFt, displacement\n0, 0.0086\n1 ,0.0090\r\n", with_stress(0.232));
  BOOST_TEST(d.t.size() == 2u);
  BOOST_TEST(d.displacement[1] == 0.0090);
}

BOOST_AUTO_TEST_CASE(stress_column_starts_a_stage_at_each_new_value) {
  const auto d = parse("time,tau,u\n0,0.2,1\n5,0.2,2\n10,0.4,3\n15,0.4,4\n20,0,2\n",
                       fit::CsvOptions{"time", "u", "tau", std::nullopt, ""});
  BOOST_TEST(d.stages.size() == 3u);
  BOOST_TEST(d.stages[1].t == 10.0);
  BOOST_TEST(d.stages[1].stress == 0.4);
  BOOST_TEST(d.stages[1].first == 2u);
  BOOST_TEST(d.stages[2].stress == 0.0);
  BOOST_TEST(d.stages[2].count == 1u);
  BOOST_TEST(d.history.at(12.0) == 0.4);
}

BOOST_AUTO_TEST_CASE(staged_stress_option_assigns_rows_to_stages) {
  fit::CsvOptions o;
  o.stress = laws::StagedHistory::parse("0:0.2,10:0.4", "--stress");
  const auto d = parse("t,displacement\n0,1\n5,2\n10,3\n15,4\n", o);
  BOOST_TEST(d.stages.size() == 2u);
  BOOST_TEST(d.stages[0].count == 2u);
  BOOST_TEST(d.stages[1].count == 2u);
}

BOOST_AUTO_TEST_CASE(bad_rows_are_rejected_with_file_line_and_column) {
  const auto o = with_stress(0.2);
  expect_error("t,displacement\n0,1\n1,nan\n", o, 3, "displacement", "not a finite number");
  expect_error("t,displacement\n0,1\n1,abc\n", o, 3, "displacement", "not a number");
  expect_error("t,displacement\n0,1\n1,\n", o, 3, "displacement", "not a number");
  expect_error("t,displacement\n0,1\n2,1\n2,1.5\n", o, 4, "t", "does not increase");
  expect_error("t,displacement\n0,1\n2,1\n1,1.5\n", o, 4, "t", "does not increase");
  expect_error("t,displacement\n-1,1\n", o, 2, "t", "negative");
  expect_error("t,displacement\n0,1\n1,2,3\n", o, 3, "", "3 cells");
  expect_error("t,disp\n0,1\n", o, 1, "displacement", "no such column");
  expect_error("time,displacement\n0,1\n", o, 1, "t", "--time-column");
  expect_error("t,displacement,tau\n0,1,x\n", with_column("tau"), 2, "tau", "not a number");
  expect_error("t,displacement\n0,1\n", with_column("tau"), 1, "tau", "--stress-column");
  // Values whose squares and sums overflow (or underflow) a double: the fit would
  // report inf or 0 parameters and an R^2 of nan.
  expect_error("t,displacement\n0,1\n1,1e300\n", o, 3, "displacement", "change the unit of this column");
  expect_error("t,displacement\n0,1\n1e-200,1\n", o, 3, "t", "1e-150 to 1e150");
  BOOST_TEST(parse("t,displacement\n0,0\n1,1e149\n", o).t.size() == 2u);  // 0 and large-but-safe values pass
}

BOOST_AUTO_TEST_CASE(empty_files_and_stages_without_points_are_rejected) {
  expect_error("", with_stress(0.2), 0, "", "empty file");
  expect_error("# only a comment\nt,displacement\n", with_stress(0.2), 0, "", "no data rows");
  fit::CsvOptions o;
  o.stress = laws::StagedHistory::parse("0:0.2,10:0.4,12:0.6", "--stress");
  expect_error("t,displacement\n0,1\n5,2\n15,4\n", o, 0, "--stress", "stage 2");
  o.stress = laws::StagedHistory::parse("5:0.2", "--stress");
  expect_error("t,displacement\n0,1\n6,2\n", o, 2, "t", "before the first stress stage");
}

BOOST_AUTO_TEST_CASE(missing_stress_is_rejected) {
  expect_error("t,displacement\n0,1\n", fit::CsvOptions{}, 0, "", "no applied stress");
}

BOOST_AUTO_TEST_CASE(folders_and_devices_are_not_data_files) {
  const auto o = with_stress(0.2);
  for (const auto& [path, words] : std::vector<std::pair<std::string, std::string>>{
           {"/dev/zero", "is not a regular file"}, {"/", "is a folder"}}) {
    try {
      (void)fit::read_creep_csv(path, o);
      BOOST_ERROR("no error for " << path);
    } catch (const fit::DataError& e) {
      BOOST_TEST(std::string(e.what()).find(words) != std::string::npos, e.what());
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()
