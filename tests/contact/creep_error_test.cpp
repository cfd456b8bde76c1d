// CreepErrorEstimate (creep_error.hpp) on its own: the stress it remembers from
// one step to the next (for the curvature of the exponential-linear scheme's
// estimate) is saved sorted, restored as saved, and taken back with a retracted
// step, so that a retried step is estimated as the first try was.
#include <boost/test/unit_test.hpp>
#include <cstdint>
#include <utility>
#include <vector>

#include "rheodda/contact/creep_error.hpp"
#include "rheodda/laws/registry.hpp"

using namespace rheodda;
using namespace rheodda::contact;

namespace {

using Stresses = std::vector<std::pair<std::uint64_t, double>>;

/// A contact locked on joint set 0 with its history in slot 0, carrying `force`
/// over a unit tributary length (tau = force) [force/length].
Contact locked(std::uint64_t id, double force) {
  Contact c;
  c.id = id;
  c.state = ContactState::locked;
  c.joint_set = 0;
  c.rheology = 0;
  c.tributary_length = 1.0;
  c.shear_force = force;
  return c;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(creep_error_estimate)

BOOST_AUTO_TEST_CASE(saved_stresses_come_back_sorted_and_a_retraction_restores_them) {
  JointSet js;
  js.name = "j";
  js.law = laws::LawRegistry::builtin().create(
      "burgers", {{"E1", 26.87}, {"E2", 192.43}, {"eta1", 34807.72}, {"eta2", 2141.23}});
  const std::vector<JointSet> joint_sets{js};
  const double dt = 2.0;  // [h]
  step::LawStep ls;
  ls.active = true;
  ls.scheme = laws::Scheme::implicit;
  const std::vector<step::LawStep> law_steps{ls};

  CreepErrorEstimate e;
  const Stresses saved{{7, 0.3}, {2, 0.1}};  // as a state file may hold them, unsorted
  e.restore(saved, 1.5, 4e-3, 2);
  BOOST_TEST((e.previous_stress() == Stresses{{2, 0.1}, {7, 0.3}}));
  BOOST_TEST(e.previous_dt() == 1.5);
  BOOST_TEST(e.error() == 4e-3);
  BOOST_TEST(e.state_changes() == 2);

  // One step of contact 2 from 0.1 to 0.2 [MPa] under the implicit scheme: its
  // error is the difference from exponential-linear, not zero under a changing
  // force; the estimate now remembers the step's start stress.
  const std::vector<Contact> start{locked(2, 0.1)}, end{locked(2, 0.2)};
  const std::vector<laws::RheologyState> histories(1);
  e.estimate(start, histories, end, joint_sets, law_steps, dt);
  BOOST_TEST(e.error() > 0.0);
  BOOST_TEST(e.state_changes() == 0);
  BOOST_TEST((e.previous_stress() == Stresses{{2, 0.1}}));
  BOOST_TEST(e.previous_dt() == dt);

  // Retracted: what it remembered before the step, no error, no changes.
  e.retract();
  BOOST_TEST((e.previous_stress() == Stresses{{2, 0.1}, {7, 0.3}}));
  BOOST_TEST(e.previous_dt() == 1.5);
  BOOST_TEST(e.error() == 0.0);
  BOOST_TEST(e.state_changes() == 0);
}

BOOST_AUTO_TEST_CASE(a_contact_on_a_law_that_locks_within_the_step_counts_as_a_state_change) {
  JointSet js;
  js.name = "j";
  js.law = laws::LawRegistry::builtin().create("maxwell", {{"E1", 10.0}, {"eta1", 100.0}});
  const std::vector<JointSet> joint_sets{js};
  CreepErrorEstimate e;
  Contact sliding = locked(3, 0.0);
  sliding.state = ContactState::sliding;
  const std::vector<Contact> start{sliding}, end{locked(3, 0.1), locked(4, 0.1)};  // 4: new, closed
  const std::vector<laws::RheologyState> histories(1);
  e.estimate(start, histories, end, joint_sets, std::vector<step::LawStep>(1), 1.0);
  BOOST_TEST(e.state_changes() == 2);
  BOOST_TEST(e.error() == 0.0);  // neither was locked at both ends
}

BOOST_AUTO_TEST_SUITE_END()
