// The O(1) state-variable update (laws/src/series_law.cpp) equals the seed's
// hereditary sum d_c(t_n) = sum_i dF_i C(t_n - t_i) (seed eqs. 4-6, with
// C(t) = (1 - exp(-E2 t/eta2))/E2 + t/eta1 from eq. 2), evaluated naively, and
// the seed's own recurrence for omega and upsilon (eqs. 9-16), on a random
// staged history whose load changes fall on step boundaries.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <random>
#include <vector>

#include "test_support.hpp"

using namespace rheodda::laws;
using namespace rheodda::laws::test;

namespace {
struct History {
  std::vector<double> t;   // t_0 = 0 < t_1 < ... < t_N [h]
  std::vector<double> dF;  // force increment at t_n, n < N [MPa]
};

// 400 steps of random length in [0.05, 60] h; at a third of the step starts
// the force jumps by a random amount in [-0.4, 0.4] MPa (loading and unloading).
History random_history(unsigned seed) {
  std::mt19937_64 gen(seed);
  std::uniform_real_distribution<double> step(0.05, 60.0), jump(-0.4, 0.4), coin(0.0, 1.0);
  History h;
  h.t.push_back(0.0);
  for (int n = 0; n < 400; ++n) {
    h.dF.push_back(n == 0 || coin(gen) < 1.0 / 3.0 ? jump(gen) : 0.0);
    h.t.push_back(h.t.back() + step(gen));
  }
  return h;
}

// The naive sum of eqs. (4)-(6) at t_n, with the law's creep compliance C.
template <class Compliance>
double naive_sum(const History& h, std::size_t n, Compliance creep_compliance, double* scale) {
  double d = 0.0;
  *scale = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double term = h.dF[i] * creep_compliance(h.t[n] - h.t[i]);
    d += term;
    *scale += std::abs(term);
  }
  return d;
}

// Advances the law along the history (force constant within each step) with
// `scheme`, checking the creep against the naive sum after every step.
// Tolerance: 1e-12 of the sum of |terms| (the round-off scale of the sum
// itself, which may cross zero under unloading).
template <class Compliance>
void check_against_sum(const ContactRheology& law, Scheme scheme, const History& h,
                       Compliance creep_compliance) {
  RheologyState state, next;
  double force = 0.0, worst = 0.0;
  for (std::size_t n = 0; n + 1 < h.t.size(); ++n) {
    force += h.dF[n];
    const auto k = law.step_constants(h.t[n + 1] - h.t[n], scheme);
    law.advance(k, state, force, force, next);
    state = next;
    double scale = 0.0;
    const double exact = naive_sum(h, n + 1, creep_compliance, &scale);
    worst = std::max(worst, std::abs(state.creep() - exact) / scale);
  }
  BOOST_TEST(worst <= 1e-12, law.name() << " " << scheme_name(scheme) << ": worst " << worst);
}
}  // namespace

BOOST_AUTO_TEST_SUITE(hereditary_sum)

BOOST_AUTO_TEST_CASE(burgers_state_update_equals_naive_hereditary_sum_on_random_staged_history) {
  for (unsigned seed : {1u, 2u, 3u}) {
    const History h = random_history(seed);
    for (const auto& r : table1()) {
      auto c = [&](double t) { return -std::expm1(-r.E2 * t / r.eta2) / r.E2 + t / r.eta1; };
      for (Scheme s : all_schemes()) check_against_sum(*burgers(r), s, h, c);
    }
  }
}

BOOST_AUTO_TEST_CASE(maxwell_kelvin_generalized_kelvin_state_update_equals_hereditary_sum) {
  const History h = random_history(7u);
  for (const auto& r : table1()) {
    for (Scheme s : all_schemes()) {
      check_against_sum(*maxwell(r), s, h, [&](double t) { return t / r.eta1; });
      check_against_sum(*kelvin(r), s, h,
                        [&](double t) { return -std::expm1(-r.E2 * t / r.eta2) / r.E2; });
      check_against_sum(*generalized_kelvin(r), s, h, [&](double t) {
        return -std::expm1(-r.E2 * t / r.eta2) / r.E2 - std::expm1(-0.5 * r.E2 * t / r.eta1) / (0.5 * r.E2);
      });
    }
  }
}

BOOST_AUTO_TEST_CASE(seed_recurrence_omega_upsilon_equals_state_update_and_hereditary_sum) {
  // The seed's recurrence (eq. 9 / 12): the creep increment over [t_n, t_n+1] is
  //   dd_{n+1} = (1 - exp(-E2 dt_{n+1}/eta2)) omega_{n+1} + upsilon_{n+1} + dF_n C(dt_{n+1}),
  //   omega_{n+1}   = sum_{i<n} dF_i/E2 exp(-E2 (t_n - t_i)/eta2)        (eq. 10)
  //                 = (omega_n + dF_{n-1}/E2) exp(-E2 dt_n/eta2)          (eq. 15)
  //   upsilon_{n+1} = sum_{i<n} dF_i dt_{n+1}/eta1                        (eq. 11, dF not F)
  //                 = (upsilon_n/dt_n + dF_{n-1}/eta1) dt_{n+1}           (eq. 16)
  // starting from omega_1 = upsilon_1 = 0 (no increment before t_0).
  const History h = random_history(11u);
  for (const auto& r : table1()) {
    const auto law = burgers(r);
    auto c = [&](double t) { return -std::expm1(-r.E2 * t / r.eta2) / r.E2 + t / r.eta1; };
    double omega = 0.0, upsilon = 0.0, d_seed = 0.0, force = 0.0, worst_sum = 0.0, worst_state = 0.0;
    RheologyState state, next;
    for (std::size_t n = 0; n + 1 < h.t.size(); ++n) {
      const double dt = h.t[n + 1] - h.t[n];
      if (n > 0) {
        const double dt_prev = h.t[n] - h.t[n - 1];
        omega = (omega + h.dF[n - 1] / r.E2) * std::exp(-r.E2 * dt_prev / r.eta2);
        upsilon = (upsilon / dt_prev + h.dF[n - 1] / r.eta1) * dt;
      }
      d_seed += -std::expm1(-r.E2 * dt / r.eta2) * omega + upsilon + h.dF[n] * c(dt);
      force += h.dF[n];
      law->advance(law->step_constants(dt, Scheme::lagged), state, force, force, next);
      state = next;
      double scale = 0.0;
      const double exact = naive_sum(h, n + 1, c, &scale);
      worst_sum = std::max(worst_sum, std::abs(d_seed - exact) / scale);
      worst_state = std::max(worst_state, std::abs(d_seed - state.creep()) / scale);
    }
    BOOST_TEST(worst_sum <= 1e-12);
    BOOST_TEST(worst_state <= 1e-12);
  }
}

BOOST_AUTO_TEST_SUITE_END()
