// The `rheodda law list` and `rheodda law curve` commands, run as a user runs
// them: the built binary (RHEODDA_BINARY), its stdout, stderr and exit code.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

#include "test_support.hpp"

using namespace rheodda::laws;
using namespace rheodda::laws::test;

namespace {
struct Run {
  int exit_code;
  std::string out, err;
};

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Runs `rheodda ARGS` through the shell, capturing stdout and stderr.
Run run(const std::string& args) {
  const std::string base = "/tmp/rheodda_law_cli_" + std::to_string(::getpid());
  const std::string cmd = std::string(RHEODDA_BINARY) + " " + args + " >" + base + ".out 2>" + base + ".err";
  const int status = std::system(cmd.c_str());
  Run r{WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(base + ".out"), slurp(base + ".err")};
  std::remove((base + ".out").c_str());
  std::remove((base + ".err").c_str());
  return r;
}

const char* kRow1 =
    "law curve burgers --param E1=26.87 --param E2=192.43 --param eta1=34807.72 "
    "--param eta2=2141.23 --t-end 200 --dt 10 ";

std::vector<std::vector<double>> parse_csv(const std::string& text, std::string* header) {
  std::istringstream in(text);
  std::getline(in, *header);
  std::vector<std::vector<double>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<double> row;
    std::istringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  return rows;
}
// "t_f = 149.9138..." as `law curve` prints it on stderr (10 significant digits).
std::string fmt_tf(double tf) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "t_f = %.10g", tf);
  return buf;
}
}  // namespace

BOOST_AUTO_TEST_SUITE(law_curve_cli)

BOOST_AUTO_TEST_CASE(law_list_prints_every_law_and_parameter_with_units) {
  const Run r = run("law list");
  BOOST_TEST(r.exit_code == 0);
  for (const auto& law : LawRegistry::builtin().laws()) {
    BOOST_TEST(r.out.find(law.name + ":") != std::string::npos, law.name);
    for (const auto& p : law.parameters) {
      BOOST_TEST(r.out.find("  " + p.name + " ") != std::string::npos, law.name << "." << p.name);
      BOOST_TEST(r.out.find(p.meaning) != std::string::npos, p.meaning);
    }
  }
  BOOST_TEST(r.out.find("MPa*h/mm") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(law_curve_prints_csv_equal_to_the_closed_form_for_each_scheme) {
  const auto& row = table1()[0];
  for (const char* scheme : {"lagged", "implicit", "exponential-linear"}) {
    const Run r = run(std::string(kRow1) + "--force 0:0.232 --scheme " + scheme);
    BOOST_TEST(r.exit_code == 0, r.err);
    std::string header;
    const auto rows = parse_csv(r.out, &header);
    BOOST_TEST(header == "t,force,displacement,exact");
    BOOST_TEST(rows.size() == 21u);  // t = 0, 10, ..., 200
    for (const auto& v : rows) {
      BOOST_REQUIRE_EQUAL(v.size(), 4u);
      const double t = v[0];
      const double exact = row.tau / row.E1 - std::expm1(-row.E2 * t / row.eta2) * row.tau / row.E2 +
                           row.tau * t / row.eta1;
      // Printed with 10 significant digits: 1e-9 relative covers the rounding.
      BOOST_TEST(v[1] == row.tau);
      BOOST_TEST(rel(v[2], exact) <= 1e-9, "t " << t);
      BOOST_TEST(rel(v[3], exact) <= 1e-9, "t " << t);
    }
  }
}

BOOST_AUTO_TEST_CASE(law_curve_relaxation_prints_force_and_exact_force) {
  const Run r = run(std::string(kRow1) + "--displacement 0:0.01 --scheme implicit");
  BOOST_TEST(r.exit_code == 0, r.err);
  std::string header;
  const auto rows = parse_csv(r.out, &header);
  BOOST_TEST(header == "t,force,displacement,exact");
  BOOST_TEST(rows.front()[1] == 26.87 * 0.01);
  for (const auto& v : rows) {
    BOOST_TEST(v[2] == 0.01);
    BOOST_TEST(rel(v[1], v[3]) <= 1e-2);  // implicit, dt = 10 h: first-order error
  }
}

BOOST_AUTO_TEST_CASE(law_curve_bad_input_exits_2_naming_the_key) {
  struct Bad { std::string args, expected; };
  const std::vector<Bad> cases = {
      {"law curve burgers --param E1=-3 --param E2=1 --param eta1=1 --param eta2=1 --force 0:1 --t-end 1 --dt 1", "'E1'"},
      {"law curve burgers --param E1=3 --param E2=1 --param eta1=nan --param eta2=1 --force 0:1 --t-end 1 --dt 1", "'eta1'"},
      {"law curve burgers --param E1=3 --param E2=1 --param eta=1 --param eta2=1 --force 0:1 --t-end 1 --dt 1", "did you mean 'eta1'"},
      {"law curve burgers --param E1=3 --param E2=1 --param eta1=1 --force 0:1 --t-end 1 --dt 1", "'eta2'"},
      {"law curve burgers --param E1=abc --param E2=1 --param eta1=1 --param eta2=1 --force 0:1 --t-end 1 --dt 1", "E1"},
      {"law curve burger --param E1=3 --force 0:1 --t-end 1 --dt 1", "did you mean 'burgers'"},
      {std::string(kRow1) + "--force 0:abc", "--force"},
      {std::string(kRow1) + "--force 5:1,2:1", "--force"},
      {std::string(kRow1) + "--force 0:1 --scheme bogus", "--scheme"},
      {std::string(kRow1) + "--force 0:1,300:0", "starts after --t-end"},
      {std::string(kRow1) + "--displacement 0:1,300:0", "--displacement"},
      {"law curve maxwell --param E1=3 --param eta1=1 --force 0:1 --t-end 1 --dt 0", "--dt"},
      {"law curve kelvin --param E2=3 --param eta2=1 --displacement 0:1 --t-end 1 --dt 1", "displacement"},
      {std::string(kRow1), "--force"},
  };
  for (const auto& c : cases) {
    const Run r = run(c.args);
    BOOST_TEST(r.exit_code == 2, c.args);
    BOOST_TEST(r.err.find(c.expected) != std::string::npos, c.args << " -> " << r.err);
    BOOST_TEST(r.out.empty(), c.args);
  }
}

BOOST_AUTO_TEST_CASE(law_curve_of_a_damage_law_prints_its_damage_and_when_it_failed) {
  // damage-burgers at tau = 0.232 MPa (examples/damage-creep-test.yaml's law):
  // Kachanov's t_f = t_r (tau_ref / tau)^r = 234 (0.2 / 0.232)^3 = 149.9 h.
  const Run r = run(
      "law curve damage-burgers --param E1=26.87 --param E2=192.43 --param eta2=2141.23 "
      "--param A=3.68e-6 --param tau_ref=0.2 --param n=4 --param t_r=234 --param r=3 "
      "--force 0:0.232 --t-end 200 --dt 0.5");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  std::string header;
  const auto rows = parse_csv(r.out, &header);
  BOOST_TEST(header.find(",damage") != std::string::npos, header);
  BOOST_TEST_REQUIRE(rows.size() > 10u);
  const std::size_t d = rows.front().size() - 1;  // the last column
  BOOST_TEST(rows.front()[d] == 0.0);
  BOOST_TEST(rows.back()[d] == 1.0);
  for (std::size_t k = 1; k < rows.size(); ++k) BOOST_TEST(rows[k][d] >= rows[k - 1][d]);  // never heals
  const double tf = 234.0 * std::pow(0.2 / 0.232, 3.0);
  BOOST_TEST(r.err.find(fmt_tf(tf)) != std::string::npos, r.err);
  // The first sample at damage 1 is the step end past t_f.
  std::size_t first = 0;
  while (rows[first][d] < 1.0) ++first;
  BOOST_TEST(rows[first][0] >= tf);
  BOOST_TEST(rows[first][0] <= tf + 0.5);
  // A law that cannot fail prints no damage column.
  const Run b = run(std::string(kRow1) + "--force 0:0.232");
  BOOST_TEST(b.out.find("damage") == std::string::npos);
  BOOST_TEST(b.err.empty(), b.err);
}

BOOST_AUTO_TEST_SUITE_END()
