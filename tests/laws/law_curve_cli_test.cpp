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
  // Kachanov's t_f = t_r (tau_ref / tau)^r = 234 (0.2 / 0.232)^3 = 149.9 h. With
  // n = r + 1 its creep is infinite at t_f: the curve ends at the last output time
  // before it (149.5 h), every value finite, and says so.
  const std::string law =
      "law curve damage-burgers --param E1=26.87 --param E2=192.43 --param eta2=2141.23 "
      "--param A=3.68e-6 --param tau_ref=0.2 --param t_r=234 --param r=3 --force 0:0.232 --t-end 200 --dt 0.5 ";
  const double tf = 234.0 * std::pow(0.2 / 0.232, 3.0);
  const Run r = run(law + "--param n=4");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  std::string header;
  const auto rows = parse_csv(r.out, &header);
  BOOST_TEST(header.find(",damage") != std::string::npos, header);
  BOOST_TEST_REQUIRE(rows.size() > 10u);
  const std::size_t d = rows.front().size() - 1;  // the last column
  BOOST_TEST(rows.front()[d] == 0.0);
  for (std::size_t k = 1; k < rows.size(); ++k) BOOST_TEST(rows[k][d] >= rows[k - 1][d]);  // never heals
  for (const auto& row : rows)
    for (double v : row) BOOST_TEST(std::isfinite(v));
  BOOST_TEST(rows.back()[0] == 149.5);
  BOOST_TEST(rows.back()[d] < 1.0);
  BOOST_TEST(r.err.find(fmt_tf(tf)) != std::string::npos, r.err);
  BOOST_TEST(r.err.find("creep is infinite") != std::string::npos, r.err);
  // With n = 2 < r + 1 the creep at failure is finite: the damage reaches 1 at t_f,
  // the rows go on to --t-end with the creep held at its value at failure.
  const Run f = run(law + "--param n=2");
  BOOST_TEST_REQUIRE(f.exit_code == 0, f.err);
  const auto frows = parse_csv(f.out, &header);
  BOOST_TEST(frows.back()[0] == 200.0);
  BOOST_TEST(frows.back()[d] == 1.0);
  std::size_t first = 0;
  while (frows[first][d] < 1.0) ++first;
  BOOST_TEST(frows[first][0] >= tf);
  BOOST_TEST(frows[first][0] <= tf + 0.5);
  for (std::size_t k = first; k < frows.size(); ++k) BOOST_TEST(frows[k][2] == frows[first][2]);
  BOOST_TEST(f.err.find("failed (damage 1) at t = " + fmt_tf(tf).substr(6)) != std::string::npos, f.err);
  // A law that cannot fail prints no damage column.
  const Run b = run(std::string(kRow1) + "--force 0:0.232");
  BOOST_TEST(b.out.find("damage") == std::string::npos);
  BOOST_TEST(b.err.empty(), b.err);
}

BOOST_AUTO_TEST_CASE(law_curve_is_accurate_or_refused_never_nan_or_absurd) {
  // The curves issue 43 found printed NaN, +-1e54 or a tenth of the exact force with
  // exit 0: each is now within 1e-5 of its closed form (relative to the initial force),
  // or refused with exit 1 and the reason, nothing on stdout.
  const std::string pl = "law curve power-law --param E1=20 --param tau_ref=0.2 ";
  for (const std::string args :
       {pl + "--param A=1e-3 --param n=100 --displacement 0:0.1 --t-end 2 --dt 1 --scheme implicit",
        pl + "--param A=1e-3 --param n=20 --displacement 0:10 --t-end 2 --dt 1 --scheme implicit",
        pl + "--param A=1e50 --param n=4 --displacement 0:0.02 --t-end 2 --dt 1 --scheme implicit",
        pl + "--param A=1e-3 --param n=20 --displacement 0:0.02 --t-end 100 --dt 10 --scheme lagged",
        pl + "--param A=1e-3 --param n=20 --displacement 0:0.02 --t-end 100 --dt 10"}) {
    const Run r = run(args);
    BOOST_TEST_REQUIRE(r.exit_code == 0, args << ": " << r.err);
    std::string header;
    const auto rows = parse_csv(r.out, &header);
    BOOST_TEST(header == "t,force,displacement,exact");
    for (const auto& v : rows) {
      for (double x : v) BOOST_TEST(std::isfinite(x), args);
      BOOST_TEST(std::abs(v[1] - v[3]) <= 1e-5 * rows.front()[1], args << " at t " << v[0]);
    }
  }
  // (100/0.2)^100 A overflows a double: refused, exit 1, with the reason.
  const Run over = run(pl + "--param A=1e300 --param n=100 --force 0:100 --t-end 1 --dt 1");
  BOOST_TEST(over.exit_code == 1);
  BOOST_TEST(over.out.empty(), over.out);
  BOOST_TEST(over.err.find("not a finite number") != std::string::npos, over.err);
  // --tolerance outside [1e-12, 1e-2]: bad input.
  BOOST_TEST(run(std::string(kRow1) + "--force 0:0.232 --tolerance 0.5").exit_code == 2);
}

BOOST_AUTO_TEST_SUITE_END()
