// Staged loading and unloading: linear laws follow Boltzmann superposition
// d(t) = sum dF_i J(t - t_i) (rheology.md; the seed's eqs. 4-6); Nishihara
// follows superposition for its spring and Kelvin parts plus the exact
// integral of <|F| - Fs> for its Bingham part, below, at and above Fs.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <functional>
#include <vector>

#include "rheodda/laws/history.hpp"
#include "test_support.hpp"

using namespace rheodda::laws;
using namespace rheodda::laws::test;

namespace {
using Compliance = std::function<double(double)>;  // J(t): total creep compliance [mm/MPa]

// Superposition written out: returns d(t) and the scale sum |dF_i J(t - t_i)|.
double superpose(const std::vector<StagedHistory::Stage>& stages, const Compliance& j, double t,
                 double* scale) {
  double d = 0.0, prev = 0.0;
  *scale = 0.0;
  for (const auto& s : stages) {
    if (s.t > t) break;
    const double term = (s.value - prev) * j(t - s.t);
    d += term;
    *scale += std::abs(term);
    prev = s.value;
  }
  return d;
}

// Load, reload higher, unload completely, reload, reverse: [h] : [MPa].
const std::vector<StagedHistory::Stage> kStages = {
    {0.0, 0.232}, {100.0, 0.5}, {150.0, 0.0}, {400.0, 0.3}, {520.0, -0.2}};

void check_linear(const ContactRheology& law, const Compliance& j) {
  const StagedHistory history(kStages);
  for (Scheme scheme : all_schemes()) {
    for (double dt : {0.5, 7.0, 33.0}) {
      double worst = 0.0, worst_lib = 0.0;
      for (const auto& s : integrate_curve(law, Control::force, history, 800.0, dt, scheme)) {
        double scale = 0.0;
        const double exact = superpose(kStages, j, s.t, &scale);
        worst = std::max(worst, std::abs(s.displacement - exact) / scale);
        worst_lib = std::max(worst_lib, std::abs(*s.exact - exact) / scale);
      }
      BOOST_TEST(worst <= 1e-12, law.name() << " " << scheme_name(scheme) << " dt " << dt << ": " << worst);
      BOOST_TEST(worst_lib <= 1e-14, law.name() << " exact_displacement: " << worst_lib);
    }
  }
}

double kelvin_j(double e, double eta, double t) { return -std::expm1(-e * t / eta) / e; }
}  // namespace

BOOST_AUTO_TEST_SUITE(superposition)

BOOST_AUTO_TEST_CASE(linear_laws_staged_loading_unloading_follow_boltzmann_superposition) {
  for (const auto& r : table1()) {
    check_linear(*burgers(r), [&](double t) { return 1 / r.E1 + kelvin_j(r.E2, r.eta2, t) + t / r.eta1; });
    check_linear(*maxwell(r), [&](double t) { return 1 / r.E1 + t / r.eta1; });
    check_linear(*kelvin(r), [&](double t) { return kelvin_j(r.E2, r.eta2, t); });
    check_linear(*generalized_kelvin(r), [&](double t) {
      return 1 / r.E1 + kelvin_j(r.E2, r.eta2, t) + kelvin_j(0.5 * r.E2, r.eta1, t);
    });
  }
}

BOOST_AUTO_TEST_CASE(burgers_unloading_recovers_springs_at_once_and_keeps_dashpot_creep) {
  const auto& r = table1()[0];
  const auto law = burgers(r);
  // Load 0.232 MPa for 100 h, then unload to zero and wait 1e5 h.
  const StagedHistory history({{0.0, r.tau}, {100.0, 0.0}});
  for (Scheme scheme : all_schemes()) {
    const auto samples = integrate_curve(*law, Control::force, history, 1e5, 1.0, scheme);
    double after = 0.0;
    for (const auto& s : samples)
      if (s.t == 100.0) after = s.displacement;
    // Just after unloading the spring E1 has recovered at once: the drop equals F/E1
    // on top of the creep accumulated up to t = 100.
    const double creep_100 = kelvin_j(r.E2, r.eta2, 100.0) * r.tau + r.tau * 100.0 / r.eta1;
    BOOST_TEST(rel(after, creep_100) <= 1e-12);
    // Long after: the Kelvin part has decayed, the dashpot displacement stays.
    BOOST_TEST(rel(samples.back().displacement, r.tau * 100.0 / r.eta1) <= 1e-12);
  }
}

BOOST_AUTO_TEST_CASE(nishihara_staged_below_at_and_above_threshold_matches_exact_staged_solution) {
  const auto& r = table1()[1];
  const double fs = 0.3;  // [MPa]
  const auto law = nishihara(r, fs);
  // Exact: spring + Kelvin by superposition, Bingham by integrating
  // sign(F)<|F| - Fs>/eta3 over each constant stage.
  struct Case { const char* what; std::vector<StagedHistory::Stage> stages; };
  const std::vector<Case> cases = {
      {"below", {{0.0, 0.1}, {50.0, 0.25}, {120.0, 0.0}}},
      {"exactly at", {{0.0, 0.2}, {50.0, fs}, {120.0, -fs}, {200.0, 0.0}}},
      {"above", {{0.0, 0.2}, {50.0, 0.45}, {120.0, 0.1}, {200.0, -0.5}, {260.0, 0.0}}}};
  for (const auto& c : cases) {
    const StagedHistory history(c.stages);
    auto exact = [&](double t) {
      double d = history.at(t) / r.E1, prev = 0.0;
      for (std::size_t i = 0; i < c.stages.size() && c.stages[i].t <= t; ++i) {
        const double f = c.stages[i].value;
        const double end = i + 1 < c.stages.size() ? std::min(c.stages[i + 1].t, t) : t;
        d += (f - prev) * kelvin_j(r.E2, r.eta2, t - c.stages[i].t);
        const double g = f > fs ? f - fs : f < -fs ? f + fs : 0.0;
        d += g * (end - c.stages[i].t) / r.eta1;
        prev = f;
      }
      return d;
    };
    for (Scheme scheme : all_schemes()) {
      for (double dt : {0.7, 10.0}) {
        double worst = 0.0, worst_lib = 0.0;
        for (const auto& s : integrate_curve(*law, Control::force, history, 300.0, dt, scheme)) {
          const double e = exact(s.t);
          const double scale = std::abs(e) + 1e-3;  // d crosses zero on reversal [mm]
          worst = std::max(worst, std::abs(s.displacement - e) / scale);
          worst_lib = std::max(worst_lib, std::abs(*s.exact - e) / scale);
        }
        BOOST_TEST(worst <= 1e-12, c.what << " " << scheme_name(scheme) << " dt " << dt << ": " << worst);
        BOOST_TEST(worst_lib <= 1e-14, c.what << " exact_displacement: " << worst_lib);
      }
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()
