// Each law under constant force reproduces its closed form to round-off at any step.
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "rheodda/laws/history.hpp"
#include "rheodda/laws/registry.hpp"

using namespace rheodda::laws;

namespace {
// The seed's Table 1: (tau [MPa], E1 [MPa], E2 [MPa], eta1 [MPa h], eta2 [MPa h]).
struct Row { double tau, e1, e2, eta1, eta2; };
const Row kTable1[] = {{0.232, 26.87, 192.43, 34807.72, 2141.23},
                       {0.424, 40.13, 249.33, 101760.29, 3236.41},
                       {0.439, 29.45, 260.76, 52869.39, 3771.63},
                       {0.512, 33.65, 305.53, 23051.02, 5736.91}};
}  // namespace

BOOST_AUTO_TEST_SUITE(closed_form)

BOOST_AUTO_TEST_CASE(burgers_table1_constant_force_matches_closed_form_at_any_step) {
  for (const auto& row : kTable1) {
    const auto law = LawRegistry::builtin().create(
        "burgers", {{"E1", row.e1}, {"E2", row.e2}, {"eta1", row.eta1}, {"eta2", row.eta2}});
    for (Scheme scheme : {Scheme::lagged, Scheme::implicit, Scheme::exponential_linear}) {
      for (double dt : {0.01, 1.0, 7.0, 200.0}) {
        const auto samples = integrate_curve(*law, Control::force, StagedHistory({{0.0, row.tau}}),
                                             200.0, dt, scheme);
        for (const auto& s : samples) {
          const double exact = law->displacement_closed_form(row.tau, s.t);
          BOOST_TEST(std::abs(s.displacement - exact) <= 1e-12 * std::abs(exact),
                     "scheme " << scheme_name(scheme) << " dt " << dt << " t " << s.t << ": "
                               << s.displacement << " vs " << exact);
        }
      }
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()
