// The registry and its parameter schemas: every law is listed with units,
// and every bad parameter, law name, history text or scheme is a LawError
// that names the offending key (with a "did you mean" hint for near misses).
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <limits>
#include <set>
#include <string>

#include "rheodda/laws/builtin_laws.hpp"
#include "rheodda/laws/history.hpp"
#include "test_support.hpp"

using namespace rheodda::laws;
using namespace rheodda::laws::test;

namespace {
const ParameterValues kBurgers = {{"E1", 26.87}, {"E2", 192.43}, {"eta1", 34807.72}, {"eta2", 2141.23}};

// Expects create() to throw a LawError whose key is `key` and whose message
// contains `key` and, if given, `fragment`.
void expect_error(const std::string& law, const ParameterValues& p, const std::string& key,
                  const std::string& fragment = "") {
  try {
    LawRegistry::builtin().create(law, p);
    BOOST_ERROR("no error for key " << key);
  } catch (const LawError& e) {
    const std::string what = e.what();
    BOOST_TEST(e.key() == key, what);
    BOOST_TEST(what.find("'" + key + "'") != std::string::npos, what);
    BOOST_TEST(what.find(fragment) != std::string::npos, what);
  }
}
ParameterValues with(ParameterValues p, const std::string& key, double v) {
  p[key] = v;
  return p;
}
ParameterValues without(ParameterValues p, const std::string& key) {
  p.erase(key);
  return p;
}
}  // namespace

BOOST_AUTO_TEST_SUITE(registry)

BOOST_AUTO_TEST_CASE(registry_lists_the_eight_laws_with_units_and_meanings) {
  std::set<std::string> names;
  for (const auto& law : LawRegistry::builtin().laws()) {
    names.insert(law.name);
    BOOST_TEST(!law.summary.empty());
    BOOST_TEST(!law.equation.empty());
    for (const auto& p : law.parameters) {
      BOOST_TEST(!p.unit.empty(), law.name << "." << p.name);
      BOOST_TEST(!p.meaning.empty(), law.name << "." << p.name);
    }
    // The factory builds the law it is registered under.
    ParameterValues p;
    for (const auto& spec : law.parameters) p[spec.name] = 1.0;
    BOOST_TEST(LawRegistry::builtin().create(law.name, p)->name() == law.name);
  }
  BOOST_TEST((names == std::set<std::string>{"burgers", "maxwell", "kelvin", "nishihara",
                                             "generalized-kelvin", "power-law",
                                             "power-law-burgers", "damage-burgers"}));
}

BOOST_AUTO_TEST_CASE(duplicate_registration_is_refused) {
  LawRegistry r;
  register_builtin_laws(r);
  BOOST_CHECK_THROW(r.add(Burgers::info()), std::logic_error);
}

BOOST_AUTO_TEST_CASE(power_law_exponents_outside_their_range_name_the_key) {
  const ParameterValues pl{{"E1", 26.87}, {"A", 1e-5}, {"tau_ref", 0.2}, {"n", 3.0}};
  expect_error("power-law", with(pl, "n", 0.5), "n", "out of range");    // n >= 1
  expect_error("power-law", with(pl, "n", 101.0), "n", "out of range");  // n <= 100
  expect_error("power-law", with(pl, "A", 0.0), "A", "out of range");
  expect_error("power-law", with(pl, "tau_ref", -1.0), "tau_ref", "out of range");
  ParameterValues db = pl;
  db["E2"] = 192.43;
  db["eta2"] = 2141.23;
  db["t_r"] = 1000.0;
  db["r"] = 3.0;
  expect_error("damage-burgers", with(db, "t_r", 0.0), "t_r", "out of range");
  expect_error("damage-burgers", with(db, "r", 0.0), "r", "out of range");  // r > 0
  expect_error("damage-burgers", without(db, "t_r"), "t_r", "needs");
}

BOOST_AUTO_TEST_CASE(non_positive_stiffness_or_viscosity_names_the_key) {
  expect_error("burgers", with(kBurgers, "E1", -1.0), "E1", "out of range");
  expect_error("burgers", with(kBurgers, "E2", 0.0), "E2", "out of range");
  expect_error("burgers", with(kBurgers, "eta1", -5.0), "eta1", "out of range");
  expect_error("burgers", with(kBurgers, "eta2", 0.0), "eta2", "out of range");
  expect_error("nishihara", {{"E1", 1}, {"E2", 1}, {"eta2", 1}, {"eta3", 1}, {"Fs", -0.1}}, "Fs",
               "out of range");
  // A zero threshold is valid (Bingham = dashpot).
  BOOST_CHECK_NO_THROW(LawRegistry::builtin().create(
      "nishihara", {{"E1", 1}, {"E2", 1}, {"eta2", 1}, {"eta3", 1}, {"Fs", 0.0}}));
}

BOOST_AUTO_TEST_CASE(nan_and_inf_parameters_name_the_key) {
  expect_error("burgers", with(kBurgers, "E1", std::numeric_limits<double>::quiet_NaN()), "E1", "finite");
  expect_error("burgers", with(kBurgers, "eta1", std::numeric_limits<double>::infinity()), "eta1", "finite");
  expect_error("maxwell", {{"E1", -std::numeric_limits<double>::infinity()}, {"eta1", 1.0}}, "E1", "finite");
}

BOOST_AUTO_TEST_CASE(unknown_key_suggests_the_nearest_name_and_missing_key_is_named) {
  expect_error("burgers", with(kBurgers, "eta_1", 1.0), "eta_1", "did you mean 'eta1'");
  expect_error("burgers", with(without(kBurgers, "E2"), "e2", 1.0), "e2", "did you mean 'E2'");
  expect_error("burgers", without(kBurgers, "eta2"), "eta2", "needs parameter");
  expect_error("kelvin", {{"E2", 1.0}, {"eta2", 1.0}, {"E1", 1.0}}, "E1", "has no parameter");
}

BOOST_AUTO_TEST_CASE(unknown_law_suggests_the_nearest_law) {
  try {
    LawRegistry::builtin().create("burger", kBurgers);
    BOOST_ERROR("no error");
  } catch (const LawError& e) {
    BOOST_TEST(e.key() == "law");
    BOOST_TEST(std::string(e.what()).find("did you mean 'burgers'") != std::string::npos, e.what());
  }
  BOOST_CHECK_THROW(LawRegistry::builtin().get("zzzz"), LawError);
  BOOST_TEST(nearest_name("zzzz", {"burgers", "maxwell"}).empty());
}

BOOST_AUTO_TEST_CASE(bad_force_history_text_names_the_option) {
  for (const char* text : {"", "0.232", "0:abc", "x:0.2", "0:0.2,", "0:0.2,10:", "10:0.1,5:0.2",
                           "-1:0.2", "0:nan", "0:inf", "0:0.2;5:0.1", "0:0.2 "}) {
    try {
      StagedHistory::parse(text, "--force");
      BOOST_ERROR("no error for '" << text << "'");
    } catch (const LawError& e) {
      BOOST_TEST(e.key() == "--force", text);
      BOOST_TEST(std::string(e.what()).find("--force") != std::string::npos, e.what());
    }
  }
  const auto h = StagedHistory::parse("0:0.232,100:0.5,150:0", "--force");
  BOOST_TEST(h.stages().size() == 3u);
  BOOST_TEST(h.at(99.9) == 0.232);
  BOOST_TEST(h.at(100.0) == 0.5);
  BOOST_TEST(h.at(1e9) == 0.0);
}

BOOST_AUTO_TEST_CASE(bad_scheme_step_and_control_name_the_key) {
  try {
    parse_scheme("explicit");
    BOOST_ERROR("no error");
  } catch (const LawError& e) {
    BOOST_TEST(e.key() == "scheme");
    BOOST_TEST(std::string(e.what()).find("exponential-linear") != std::string::npos);
  }
  for (Scheme s : all_schemes()) BOOST_TEST((parse_scheme(scheme_name(s)) == s));
  const auto law = burgers(table1()[0]);
  const StagedHistory f({{0.0, 0.2}});
  for (double dt : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN()}) {
    try {
      integrate_curve(*law, Control::force, f, 10.0, dt, Scheme::implicit);
      BOOST_ERROR("no error");
    } catch (const LawError& e) {
      BOOST_TEST(e.key() == "dt");
    }
  }
  BOOST_CHECK_THROW(integrate_curve(*law, Control::force, f, -1.0, 1.0, Scheme::implicit), LawError);
  // A held displacement on a law without instantaneous spring would need infinite force.
  BOOST_CHECK_THROW(integrate_curve(*kelvin(table1()[0]), Control::displacement, f, 10.0, 1.0,
                                    Scheme::implicit),
                    LawError);
}

BOOST_AUTO_TEST_SUITE_END()
