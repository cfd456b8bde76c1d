// ContactSystem at the contact level: springs, Mohr-Coulomb friction, the
// open-close check, contact transfer and rollback, with hand-made blocks and a
// small dense solver standing in for the host.
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "rheodda/contact/contact_system.hpp"
#include "rheodda/laws/registry.hpp"
#include "test_blocks.hpp"

using namespace rheodda::contact;
using rheodda::contact::testing::Scene;

namespace {

/// Dense K and F of a few blocks (the host's job, in miniature).
class DenseSink final : public SystemSink {
 public:
  explicit DenseSink(int blocks) : K(Eigen::MatrixXd::Zero(6 * blocks, 6 * blocks)),
                                   F(Eigen::VectorXd::Zero(6 * blocks)) {}
  void add_stiffness(int i, int j, const Mat6& k) override {
    K.block<6, 6>(6 * i, 6 * j) += k;
    if (i != j) K.block<6, 6>(6 * j, 6 * i) += k.transpose();
  }
  void add_load(int i, const Vec6& f) override { F.segment<6>(6 * i) += f; }
  Eigen::MatrixXd K;
  Eigen::VectorXd F;
};

/// One step of blocks 1.. on a fixed block 0 [SI]: inertia 2M/dt^2 on the
/// translations of block 1 (the DDA step from rest is D = F dt^2 / 2M, exact
/// for a constant force), a stiff diagonal on its rotation and strains, the
/// load `load` on block 1; open-close iteration to no state change.
struct StepResult {
  Eigen::VectorXd D;
  int iterations = 0;
};
StepResult solve_step(ContactSystem& cs, const Scene& s, double mass, double dt, const Vec6& load,
                      double rigid = 1e13) {
  const int n = static_cast<int>(s.views().size());
  cs.begin_step(s.views(), {.max_displacement = 1e-4});
  StepResult r;
  for (r.iterations = 1; r.iterations <= 20; ++r.iterations) {
    DenseSink sink(n);
    cs.assemble(s.views(), sink);
    for (int b = 1; b < n; ++b) {
      sink.K(6 * b, 6 * b) += 2.0 * mass / (dt * dt);
      sink.K(6 * b + 1, 6 * b + 1) += 2.0 * mass / (dt * dt);
      for (int k = 2; k < 6; ++k) sink.K(6 * b + k, 6 * b + k) += rigid;
      sink.F.segment<6>(6 * b) += load;
    }
    // Block 0 fixed: solve for the others only.
    const int m = 6 * (n - 1);
    r.D = Eigen::VectorXd::Zero(6 * n);
    r.D.tail(m) = sink.K.bottomRightCorner(m, m).ldlt().solve(sink.F.tail(m));
    if (cs.check(s.views(), r.D).state_changes == 0) break;
  }
  cs.end_step(s.views(), r.D);
  return r;
}

ContactSettings settings(double penalty) {
  ContactSettings st;
  st.penalty = penalty;
  st.penetration_ratio = 1.0;  // no penalty raise in these tests
  return st;
}

JointSet joint(double phi_deg) {
  JointSet j;
  j.name = "joint";
  j.friction_angle = phi_deg;
  return j;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(contact_system)

BOOST_AUTO_TEST_CASE(a_refused_joint_set_is_named_by_index_and_key_as_data) {
  // The scene layer points at the joint set's entry from these, without reading the message.
  JointSet good, bad;
  good.name = "bedding";
  good.friction_angle = 30.0;
  bad.name = "cross";
  bad.friction_angle = 30.0;
  bad.cohesion = -1.0;
  ContactSettings settings;
  settings.penalty = 1e9;
  try {
    ContactSystem cs({good, bad}, settings);
    BOOST_ERROR("a negative cohesion was accepted");
  } catch (const JointSetError& e) {
    BOOST_TEST(e.joint_set() == 1u);
    BOOST_TEST(e.key() == "cohesion");
    BOOST_TEST(std::string(e.what()) == "joint_sets.cross.cohesion: -1 is out of range [0, inf] [stress]");
  }
  bad.cohesion = 0.0;
  bad.restitution = 2.0;
  try {
    ContactSystem cs({bad, good}, settings);
    BOOST_ERROR("a restitution of 2 was accepted");
  } catch (const JointSetError& e) {
    BOOST_TEST(e.joint_set() == 0u);
    BOOST_TEST(e.key() == "restitution");
  }
}

BOOST_AUTO_TEST_CASE(normal_springs_carry_the_weight_of_a_resting_block) {
  Scene s;
  s.add_rect(0, 0, 2, 1);
  s.add_rect(0.5, 1, 1.5, 1.5);
  const double pn = 1e10, W = 12740.0;  // weight per unit thickness [N/m]
  ContactSystem cs({joint(30.0)}, settings(pn));
  Vec6 load = Vec6::Zero();
  load(1) = -W;
  // Static: a huge "mass" step is the same as no inertia; use a tiny mass.
  solve_step(cs, s, 1e-12, 1.0, load);
  const auto c = cs.contacts();
  BOOST_TEST_REQUIRE(c.size() == 2u);
  double N = 0.0;
  for (const Contact& k : c) {
    BOOST_TEST((k.state == ContactState::locked));
    BOOST_TEST(k.normal_force == W / 2, boost::test_tools::tolerance(1e-9));
    BOOST_TEST(k.penetration == W / (2 * pn), boost::test_tools::tolerance(1e-9));
    BOOST_TEST(std::abs(k.shear_force) < 1e-9 * W);
    N += k.normal_force;
  }
  BOOST_TEST(N == W, boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(block_on_an_incline_accelerates_by_g_sin_minus_cos_tan_phi_or_holds) {
  // Incline as tilted gravity on an axis-aligned scene: a = g (sin a - cos a tan phi).
  const double alpha = 30.0 * std::numbers::pi / 180.0, g = 9.81, dt = 1e-3;
  for (double phi : {20.0, 29.0, 31.0, 40.0}) {
    Scene s;
    s.add_rect(0, 0, 4, 1);
    s.add_rect(1, 1, 3, 1.2);  // flat: the overturning moment barely unloads a contact
    const double mass = 2600.0 * 0.4, W = mass * g;
    const double pn = 1e14;  // stiff: penetration does not feed the inertia term
    ContactSystem cs({joint(phi)}, settings(pn));
    Vec6 load = Vec6::Zero();
    load(0) = -W * std::sin(alpha);
    load(1) = -W * std::cos(alpha);
    // Two steps so that the friction uses a settled normal force.
    solve_step(cs, s, mass, dt, load);
    const auto r = solve_step(cs, s, mass, dt, load);
    const double tan_phi = std::tan(phi * std::numbers::pi / 180.0);
    int sliding = 0;
    for (const Contact& k : cs.contacts()) sliding += k.state == ContactState::sliding;
    if (tan_phi < std::tan(alpha)) {
      BOOST_TEST(sliding == 2);
      // The mini host carries no velocity and moves no vertex: each step is a
      // step from rest, D = a dt^2 / 2 exactly.
      const double a = g * (std::sin(alpha) - std::cos(alpha) * tan_phi);
      BOOST_TEST(-r.D(6) == 0.5 * a * dt * dt, boost::test_tools::tolerance(2e-3));
    } else {
      // Held: at least one contact stays locked and the contacts' shear forces
      // balance the down-slope weight (the inertia of a block at rest is ~0).
      BOOST_TEST(sliding < 2);
      if (phi >= 40.0) BOOST_TEST(sliding == 0);
      double S = 0.0;
      for (const Contact& k : cs.contacts()) S += k.shear_force;
      BOOST_TEST(std::abs(S) == W * std::sin(alpha), boost::test_tools::tolerance(1e-3));
      BOOST_TEST(std::abs(r.D(6)) < 1e-3 * 0.5 * g * std::sin(alpha) * dt * dt);
    }
  }
}

BOOST_AUTO_TEST_CASE(contact_moves_to_the_adjacent_edge_keeping_identity_state_and_rheology_slot) {
  Scene s;
  // Base with a top made of two collinear edges: 2: (2,1)->(1,1), 3: (1,1)->(0,1).
  s.add({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {0, 1}});
  const double x0 = 0.9;
  s.add({{x0, 1.0 - 1e-6}, {x0 + 0.1, 1.2}, {x0 - 0.1, 1.2}});  // triangle, one vertex down
  JointSet js = joint(30.0);
  js.law = rheodda::laws::LawRegistry::builtin().create(
      "burgers", {{"E1", 1.0}, {"eta1", 1.0}, {"E2", 1.0}, {"eta2", 1.0}});
  ContactSystem cs({js}, settings(1e10));
  const Eigen::VectorXd D = Eigen::VectorXd::Zero(12);
  std::uint64_t id = 0;
  ContactState last = ContactState::open;
  // The vertex walks from edge 3 over the shared vertex (1, 1) onto edge 2 in
  // steps of 0.4 d0 (d0 = 2.5e-4 m), through the vertex-vertex zone. The walk
  // is imposed (D = 0), so the stretched shear spring eventually slides.
  const double step = 1e-4;
  int on_edge2 = 0;
  for (int k = 0; k < 2000 && on_edge2 < 20; ++k) {
    cs.begin_step(s.views(), {.max_displacement = 1e-4});
    BOOST_TEST_REQUIRE(cs.trial_contacts().size() == 1u);
    const Contact& t = cs.trial_contacts()[0];
    if (k == 0) {
      id = t.id;
      BOOST_TEST((t.state == ContactState::locked));  // starts penetrating
    } else {
      BOOST_TEST(t.id == id);
      BOOST_TEST((t.state == last));  // carried over, also onto the next edge
    }
    BOOST_TEST(t.rheology == 0);
    BOOST_TEST((t.key.edge == 3 || t.key.edge == 2));
    cs.check(s.views(), D);
    cs.end_step(s.views(), D);
    BOOST_TEST(cs.rheology_states().size() == 1u);
    last = cs.contacts()[0].state;
    BOOST_TEST((last != ContactState::open));
    on_edge2 += cs.contacts()[0].key.edge == 2;
    s.translate(1, {step, 0.0});
  }
  BOOST_TEST(on_edge2 == 20);
  BOOST_TEST(cs.stats().transferred == 1);
}

BOOST_AUTO_TEST_CASE(contacts_without_a_law_have_no_rheology_slot) {
  Scene s;
  s.add_rect(0, 0, 2, 1);
  s.add_rect(0.5, 1, 1.5, 1.5);
  ContactSystem cs({joint(30.0)}, settings(1e10));
  Vec6 load = Vec6::Zero();
  load(1) = -1e4;
  solve_step(cs, s, 1e-12, 1.0, load);
  for (const Contact& c : cs.contacts()) BOOST_TEST(c.rheology == -1);
  BOOST_TEST(cs.rheology_states().empty());
}

BOOST_AUTO_TEST_CASE(abandon_step_restores_the_step_start_contact_states_exactly) {
  Scene s;
  s.add_rect(0, 0, 2, 1);
  s.add_rect(0.5, 1, 1.5, 1.5);
  ContactSystem cs({joint(30.0)}, settings(1e10));
  Vec6 load = Vec6::Zero();
  load(1) = -1e4;
  solve_step(cs, s, 1e-12, 1.0, load);
  const std::vector<Contact> before(cs.contacts().begin(), cs.contacts().end());
  BOOST_TEST_REQUIRE(before.size() == 2u);

  cs.begin_step(s.views(), {.max_displacement = 1e-4});
  const std::vector<Contact> trial0(cs.trial_contacts().begin(), cs.trial_contacts().end());
  // A trial that lifts the block: both contacts open.
  Eigen::VectorXd D = Eigen::VectorXd::Zero(12);
  D(7) = 1e-3;
  BOOST_TEST(cs.check(s.views(), D).state_changes == 2);
  cs.abandon_step();

  auto same = [](const Contact& a, const Contact& b) {
    return a.id == b.id && a.key == b.key && a.state == b.state &&
           a.locking_ratio == b.locking_ratio && a.normal_force == b.normal_force &&
           a.shear_force == b.shear_force && a.shear_displacement == b.shear_displacement &&
           a.intact == b.intact && a.slide_direction == b.slide_direction;
  };
  BOOST_TEST_REQUIRE(cs.contacts().size() == before.size());
  for (size_t k = 0; k < before.size(); ++k) BOOST_TEST(same(cs.contacts()[k], before[k]));
  // Redoing the step starts from exactly the same trial states.
  cs.begin_step(s.views(), {.max_displacement = 1e-4});
  BOOST_TEST_REQUIRE(cs.trial_contacts().size() == trial0.size());
  for (size_t k = 0; k < trial0.size(); ++k) BOOST_TEST(same(cs.trial_contacts()[k], trial0[k]));
}

BOOST_AUTO_TEST_CASE(extrapolate_combines_matching_records_and_refuses_different_states) {
  // Step doubling's Richardson step (docs/reference/step-controls.md): from the same
  // records, a "coarse" and a "fine" continuation; the fine records become
  // 2 fine - coarse when both hold the same contacts in the same states.
  Scene s;
  s.add_rect(0, 0, 4, 1);
  s.add_rect(1, 1, 2, 1.5);
  ContactSystem start({joint(30.0)}, settings(1e10));
  Vec6 load = Vec6::Zero();
  load(1) = -1e4;
  solve_step(start, s, 1300.0, 1e-3, load);
  ContactSystem coarse = start, fine = start;
  Vec6 push = load;
  push(0) = -1e3;  // below friction: 1e4 N tan 30 deg = 5.8e3 N
  solve_step(coarse, s, 1300.0, 1e-3, push);
  push(0) = -2e3;
  solve_step(fine, s, 1300.0, 1e-3, push);
  BOOST_TEST_REQUIRE(fine.contacts().size() == 2u);
  for (size_t k = 0; k < 2; ++k) {
    BOOST_TEST_REQUIRE((fine.contacts()[k].state == ContactState::locked));
    BOOST_TEST_REQUIRE((coarse.contacts()[k].state == ContactState::locked));
  }
  const std::vector<Contact> f(fine.contacts().begin(), fine.contacts().end());
  const std::vector<Contact> c(coarse.contacts().begin(), coarse.contacts().end());
  BOOST_TEST(fine.extrapolate(coarse));
  for (size_t k = 0; k < 2; ++k) {
    const Contact& x = fine.contacts()[k];
    BOOST_TEST(x.id == f[k].id);
    BOOST_TEST(x.shear_force == 2 * f[k].shear_force - c[k].shear_force);
    BOOST_TEST(x.normal_force == 2 * f[k].normal_force - c[k].normal_force);
    BOOST_TEST(x.shear_displacement == 2 * f[k].shear_displacement - c[k].shear_displacement);
    BOOST_TEST(x.locking_ratio == 2 * f[k].locking_ratio - c[k].locking_ratio);
    BOOST_TEST(x.penetration == 2 * f[k].penetration - c[k].penetration);
    BOOST_TEST(f[k].shear_force != c[k].shear_force);  // the two continuations differ
  }
  // A push beyond friction slides: the states differ, nothing is combined.
  ContactSystem sliding = start;
  push(0) = -8e3;
  solve_step(sliding, s, 1300.0, 1e-3, push);
  for (const Contact& x : sliding.contacts()) BOOST_TEST_REQUIRE((x.state == ContactState::sliding));
  const std::vector<Contact> before(sliding.contacts().begin(), sliding.contacts().end());
  BOOST_TEST(!sliding.extrapolate(coarse));
  for (size_t k = 0; k < before.size(); ++k) {
    BOOST_TEST(sliding.contacts()[k].shear_force == before[k].shear_force);
    BOOST_TEST(sliding.contacts()[k].shear_displacement == before[k].shear_displacement);
  }
}

BOOST_AUTO_TEST_CASE(slide_to_lock_counts_as_a_state_change) {
  Scene s;
  s.add_rect(0, 0, 4, 1);
  s.add_rect(1, 1, 2, 1.5);
  ContactSystem cs({joint(10.0)}, settings(1e10));
  Vec6 load = Vec6::Zero();
  load(0) = -5e3;
  load(1) = -1e4;
  solve_step(cs, s, 1300.0, 1e-3, load);  // slides in -x
  for (const Contact& c : cs.contacts()) BOOST_TEST((c.state == ContactState::sliding));
  cs.begin_step(s.views(), {.max_displacement = 1e-4});
  Eigen::VectorXd D = Eigen::VectorXd::Zero(12);
  D(6) = +1e-6;  // the trial moves against the sliding direction
  D(7) = -1e-7;  // and presses on the base (N = 1e10 x 1e-7 per contact): friction acts
  const CheckResult r = cs.check(s.views(), D);
  BOOST_TEST(r.state_changes == 2);
  BOOST_TEST(r.changes.stuck == 2);  // told apart by kind
  BOOST_TEST(r.changes.closed + r.changes.opened + r.changes.slipped + r.changes.refinements == 0);
  for (const Contact& c : cs.trial_contacts()) BOOST_TEST((c.state == ContactState::locked));
  cs.abandon_step();
}

BOOST_AUTO_TEST_CASE(stick_keeps_force_keeps_the_friction_force_through_a_stick_and_shi_restarts_the_spring) {
  // The block slides in -x on the base's top edge (edge direction -x, so the
  // slip and the friction force are positive along the edge). A trial that
  // moves it back by 1e-8 m sticks it. With stick_keeps_force its shear spring
  // then carries the friction force F = N tan(phi) it slid against, less
  // k_s x 1e-8: the force is continuous through the stick. By default (Shi's
  // rule) the spring restarts unstretched: -k_s x 1e-8 alone.
  for (const bool keep : {true, false}) {
  BOOST_TEST_CONTEXT("stick_keeps_force " << keep) {
  Scene s;
  s.add_rect(0, 0, 4, 1);
  s.add_rect(1, 1, 2, 1.5);
  ContactSettings st = settings(1e10);
  st.stick_keeps_force = keep;
  ContactSystem cs({joint(10.0)}, st);
  Vec6 load = Vec6::Zero();
  load(0) = -5e3;
  load(1) = -1e4;
  solve_step(cs, s, 1300.0, 1e-3, load);
  std::vector<double> friction;
  for (const Contact& c : cs.contacts()) {
    BOOST_TEST_REQUIRE((c.state == ContactState::sliding));
    BOOST_TEST_REQUIRE(c.shear_force > 0.0);
    BOOST_TEST(c.shear_force == c.normal_force * std::tan(10.0 * std::numbers::pi / 180.0),
               boost::test_tools::tolerance(1e-12));
    friction.push_back(c.shear_force);
  }
  cs.begin_step(s.views(), {.max_displacement = 1e-4});
  Eigen::VectorXd D = Eigen::VectorXd::Zero(12);
  D(6) = +1e-8;  // back against the slip
  D(7) = -1e-6;  // pressed on the base harder than before: the stuck spring holds
  BOOST_TEST_REQUIRE(cs.check(s.views(), D).changes.stuck == 2);
  cs.end_step(s.views(), D);
  const double ks = 1e10 / 2.5;  // penalty shear spring p_n / shear_normal_ratio [Pa]
  for (size_t k = 0; k < friction.size(); ++k) {
    const Contact& c = cs.contacts()[k];
    BOOST_TEST((c.state == ContactState::locked));
    // To 1e-8: the locking point is kept as a fraction of the 4 m edge, so it
    // is known to eps x 4 m = 9e-16 m, i.e. k_s x 9e-16 = 4e-6 N/m of 740 N/m.
    const double expected = (keep ? friction[k] : 0.0) - ks * 1e-8;
    BOOST_TEST(c.shear_force == expected, boost::test_tools::tolerance(1e-8));
  }
  }
  }
}

BOOST_AUTO_TEST_CASE(check_tells_closing_opening_and_slipping_apart) {
  // A block resting on a fixed base (two locked edge-edge contacts) and a
  // second block 1 mm above the base's right end (two open contacts, within
  // the search distance); trial displacements that lift the first block, push
  // the second one down onto the base, then shear the first one.
  Scene s;
  s.add_rect(0, 0, 4, 1);
  s.add_rect(0.5, 1, 1.5, 1.5);
  s.add_rect(2.5, 1.001, 3.5, 1.5);
  ContactSystem cs({joint(30.0)}, settings(1e10));
  cs.begin_step(s.views(), {.max_displacement = 1e-3});
  int open = 0, locked = 0;
  for (const Contact& c : cs.trial_contacts()) {
    if (c.state == ContactState::open) ++open;
    if (c.state == ContactState::locked) ++locked;
  }
  BOOST_TEST_REQUIRE(open == 2);
  BOOST_TEST_REQUIRE(locked == 2);
  Eigen::VectorXd D = Eigen::VectorXd::Zero(18);
  D(7) = 1e-4;     // block 1 lifts off: its two contacts open
  D(13) = -2e-3;   // block 2 moves 2 mm down: its two contacts close
  CheckResult r = cs.check(s.views(), D);
  BOOST_TEST(r.changes.opened == 2);
  BOOST_TEST(r.changes.closed == 2);
  BOOST_TEST(r.changes.slipped + r.changes.stuck + r.changes.refinements == 0);
  BOOST_TEST(r.state_changes == 4);
  cs.abandon_step();

  // Block 1 pressed down 1e-6 m (normal force 1e4 N per contact) and moved
  // 1e-5 m sideways: the shear spring (p / 2.5 x 1e-5 = 4e4 N) exceeds
  // N tan 30 deg = 5.8e3 N, both contacts slip.
  cs.begin_step(s.views(), {.max_displacement = 1e-3});
  D.setZero();
  D(7) = -1e-6;
  D(6) = 1e-5;
  r = cs.check(s.views(), D);
  BOOST_TEST(r.changes.slipped == 2);
  BOOST_TEST(r.changes.closed == 0);  // block 2 stays clear of the base
  BOOST_TEST(r.changes.opened + r.changes.stuck + r.changes.refinements == 0);
  BOOST_TEST(r.state_changes == 2);
  cs.abandon_step();
}

BOOST_AUTO_TEST_CASE(an_absurd_iterate_does_not_blind_the_next_one_to_a_contact_that_closes) {
  // The force resolution (forces below force_resolution x the largest normal force of the last
  // iterate count as zero) must not be taken from an iterate that sent a block far: a static
  // step's solve moves a block its contacts no longer hold by g dt^2/2 (1e8 m at creep steps),
  // its contacts then carry 1e20 N/m, and judged at that scale the next trial's open contacts
  // did not close however deep they went, so that the trial changed nothing and was accepted
  // (the 744-block slope at 26.4 d: a block 2.4 mm into the foundation, docs/notes/
  // rock-mass-steps.md, "A resolution taken from an absurd iterate"). The scale is now capped
  // at the stiffest spring's force at the allowed penetration (here 1e10 N/m x 1e-3 x w0 =
  // 2e7 N/m). The scene of the test above: block 1 locked on the base, block 2 1 mm above it.
  Scene s;
  s.add_rect(0, 0, 4, 1);
  s.add_rect(0.5, 1, 1.5, 1.5);
  s.add_rect(2.5, 1.001, 3.5, 1.5);
  ContactSettings st = settings(1e10);
  st.penetration_ratio = 1e-3;  // allowed penetration 2 mm (w0 = 2 m)
  ContactSystem cs({joint(30.0)}, st);
  cs.begin_step(s.views(), {.max_displacement = 1e-3});
  Eigen::VectorXd D = Eigen::VectorXd::Zero(18);
  D(7) = -1e3;  // an absurd iterate: block 1 driven 1 km into the base (N = 1e13 N/m)
  BOOST_TEST_REQUIRE(cs.check(s.views(), D).state_changes == 0);  // its contacts stay locked
  D(7) = -1e-6;   // the next trial: block 1 pressed 1e-6 m (N = 1e4 N/m per contact) ...
  D(13) = -1.1e-3;  // ... and block 2 moved 1.1 mm down, 0.1 mm into the base (N = 1e6 N/m)
  CheckResult r = cs.check(s.views(), D);
  BOOST_TEST(r.changes.closed == 2);
  BOOST_TEST(r.state_changes == 2);
  cs.abandon_step();

  // An iterate within the allowed penetration sets the resolution as before: after one that
  // presses block 1 by 1e-3 m (N = 1e7 N/m, resolution 1e4 N/m), block 2's contacts close
  // at 1e-6 m of penetration (N = 1e4 N/m) only when their force exceeds that.
  cs.begin_step(s.views(), {.max_displacement = 1e-3});
  D.setZero();
  D(7) = -1e-3;
  BOOST_TEST_REQUIRE(cs.check(s.views(), D).state_changes == 0);
  D(13) = -1.0005e-3;  // 0.5 um into the base: 5e3 N/m, below the resolution
  BOOST_TEST(cs.check(s.views(), D).changes.closed == 0);
  D(13) = -1.002e-3;  // 2 um: 2e4 N/m, above it
  BOOST_TEST(cs.check(s.views(), D).changes.closed == 2);
  cs.abandon_step();
}

BOOST_AUTO_TEST_CASE(penetration_beyond_the_allowed_ratio_raises_the_penalty) {
  Scene s;
  s.add_rect(0, 0, 2, 1);
  s.add_rect(0.5, 1, 1.5, 1.5);
  ContactSettings st;
  st.penalty = 1e6;
  st.penetration_ratio = 1e-4;  // allowed: 1e-4 w0 = 1e-4 m
  ContactSystem cs({joint(30.0)}, st);
  Vec6 load = Vec6::Zero();
  load(1) = -1e4;  // penetration W / (2 pn) = 5e-3 m
  solve_step(cs, s, 1e-12, 1.0, load);
  BOOST_TEST(cs.last_max_penetration() == 5e-3, boost::test_tools::tolerance(1e-6));
  BOOST_TEST(cs.penalty() == 2e6);
}

BOOST_AUTO_TEST_CASE(a_vertex_deep_inside_another_block_is_no_new_contact) {
  // A step corner 0.5 m inside the next block's base line but within a large
  // search distance: the vertex-vertex pair is found, yet no contact is made.
  Scene s;
  s.add({{0, -1}, {2, -1}, {2, 0.5}, {1, 0.5}, {1, 0}, {0, 0}});  // step of 0.5 m at x = 1
  s.add_rect(0.0, 0.0, 1.0, 2.0);  // its right side stands against the riser
  ContactSettings st = settings(1e10);
  st.penetration_ratio = 1e-4;  // allowed penetration 1e-4 w0 = 1.5e-4 m
  ContactSystem cs({joint(30.0)}, st);
  cs.begin_step(s.views(), {.max_displacement = 0.4});  // search distance 1 m > step height
  for (const Contact& c : cs.trial_contacts()) BOOST_TEST(c.penetration <= 0.0 + 1e-12);
  for (const Contact& c : cs.trial_contacts())
    BOOST_TEST(!(c.key.vblock == 0 && c.key.vertex == 3 && c.key.eblock == 1 && c.key.edge == 0));
}

BOOST_AUTO_TEST_CASE(bad_settings_and_joint_sets_are_rejected_with_the_key) {
  BOOST_CHECK_THROW(ContactSystem({joint(30.0)}, settings(0.0)), std::invalid_argument);
  JointSet j = joint(30.0);
  j.cohesion = -1.0;
  try {
    ContactSystem cs({j}, settings(1e10));
    BOOST_FAIL("no throw");
  } catch (const std::invalid_argument& e) {
    BOOST_TEST(std::string(e.what()).find("cohesion") != std::string::npos);
  }
}

BOOST_AUTO_TEST_SUITE_END()
