// The law interface's split (laws/contact_rheology.hpp, docs/design/law-interface.md,
// "What a law must give, and what it may"): a law that writes only the essence
// builds, is driven as any law is, and answers the capabilities as a law without
// them does.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <limits>
#include <vector>

#include "rheodda/laws/contact_rheology.hpp"
#include "rheodda/laws/history.hpp"

using namespace rheodda::laws;

namespace {

/// A lone linear dashpot eta, implicit: Delta d_c = dt F_e / eta. Only the
/// essence is written.
class Dashpot final : public ContactRheology {
 public:
  explicit Dashpot(double eta) : parameters_{{"eta", eta}}, eta_(eta) {}
  std::string_view name() const override { return "dashpot"; }
  const ParameterValues& parameters() const override { return parameters_; }
  int internal_count() const override { return 1; }
  StepConstants step_constants(double dt, Scheme scheme) const override {
    StepConstants k;
    k.dt = dt, k.scheme = scheme, k.count = 1;
    k.unit[0].dt_over_eta = dt / eta_;
    return k;
  }
  Linearization linearize(const StepConstants& k, const RheologyState&, double, double) const override {
    return {0.0, k.unit[0].dt_over_eta};
  }
  double advance(const StepConstants& k, const RheologyState& old, double, double force_end,
                 RheologyState& next) const override {
    next = old;
    next.q[0] += k.unit[0].dt_over_eta * force_end;
    return next.q[0] - old.q[0];
  }

 private:
  ParameterValues parameters_;
  double eta_;
};

}  // namespace

BOOST_AUTO_TEST_SUITE(law_interface)

BOOST_AUTO_TEST_CASE(a_law_of_the_essence_alone_answers_the_capabilities_as_a_law_without_them) {
  const Dashpot law(4.0);
  const ContactRheology& l = law;
  BOOST_TEST(!l.instantaneous_stiffness());                          // no series spring
  BOOST_TEST(!l.is_linear());                                        // claims nothing: ...
  BOOST_TEST((l.linearity() == Linearity::piecewise_affine));        // ... linearized at every iterate
  BOOST_TEST(std::isinf(l.linear_limit()));
  BOOST_TEST(std::isnan(l.creep_closed_form(1.0, 1.0)));             // no closed form
  BOOST_TEST(std::isnan(l.displacement_closed_form(1.0, 1.0)));
  BOOST_TEST(!l.relaxation_modulus(1.0));
  BOOST_TEST(!l.failure_time(1.0));                                  // never fails
  BOOST_TEST(std::isinf(l.time_to_failure(RheologyState{}, 1.0)));
  BOOST_TEST(!l.failure_in_step(l.step_constants(1.0, Scheme::implicit), RheologyState{}, 1.0, 1.0));
}

BOOST_AUTO_TEST_CASE(a_law_of_the_essence_alone_is_driven_as_any_law) {
  const Dashpot law(4.0);
  // A force of 2 held for 10: creep 2 * 10 / 4 = 5, step by step.
  const StagedHistory force(std::vector<StagedHistory::Stage>{{0.0, 2.0}});
  const auto curve = integrate_curve(law, Control::force, force, 10.0, 0.5, Scheme::implicit);
  BOOST_TEST(curve.back().t == 10.0);
  BOOST_TEST(curve.back().displacement == 5.0, boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_SUITE_END()
