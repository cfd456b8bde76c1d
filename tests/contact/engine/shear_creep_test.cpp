// The seed's shear creep test (Section 4, Figure 6) run by the DDA engine:
// block A on a fixed block B under a normal force F1 and a shear force F2
// below the friction limit. The joint's relative shear displacement (read from
// the contacts) follows each law's closed form. Units MPa, mm, h.
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "creep_scene.hpp"

using namespace rheodda;
using namespace rheodda::testing;

namespace {

/// Runs the creep scene to t_end and returns the largest deviation of the
/// joint's shear displacement from `exact(t)` over the accepted steps,
/// relative to exact(t), or to `scale` [mm] when given.
template <class Exact>
double creep_error(const CreepScene& scene, laws::Scheme scheme, double t_end, Exact exact,
                   double* last = nullptr, std::optional<double> scale = std::nullopt) {
  contact::ContactSettings settings = core::contact_settings_for(scene.model);
  settings.scheme = scheme;
  contact::ContactSystem contacts({scene.joint}, settings);
  core::ContactAdapter adapter(contacts);
  core::Engine engine(scene.model, adapter);
  double worst = 0.0;
  while (engine.time() < t_end - 1e-9) {
    engine.step();
    const double d = joint_shear(contacts);
    const double e = exact(engine.time());
    worst = std::max(worst, std::abs(d - e) / scale.value_or(e));
    if (last) *last = d;
  }
  return worst;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(shear_creep)

BOOST_AUTO_TEST_CASE(table1_burgers_joints_follow_the_closed_form_within_half_a_percent) {
  // Every row of the seed's Table 1, 0-200 h in steps of 2 h, implicit and
  // exponential-linear: d(t) = tau/E1 + tau/E2 (1 - exp(-E2 t/eta2)) + tau t/eta1
  // (the seed's eqs. 20-21) within 0.5 % at every step.
  for (const Table1Row& row : kTable1)
    for (laws::Scheme scheme : {laws::Scheme::implicit, laws::Scheme::exponential_linear}) {
      BOOST_TEST_CONTEXT("tau " << row.tau << " " << laws::scheme_name(scheme)) {
        auto law = table1_burgers(row);
        CreepScene scene(law, row.sigma, row.tau, 2.0);
        double d200 = 0.0;
        const double worst = creep_error(
            scene, scheme, 200.0, [&](double t) { return law->displacement_closed_form(row.tau, t); },
            &d200);
        BOOST_TEST_MESSAGE("Table 1 tau = " << row.tau << " MPa, " << laws::scheme_name(scheme)
                                            << ": d(200 h) = " << d200 << " mm (closed form "
                                            << law->displacement_closed_form(row.tau, 200.0)
                                            << "), max relative error " << worst);
        BOOST_TEST(worst < 0.005);
      }
    }
}

BOOST_AUTO_TEST_CASE(a_block_tilted_onto_its_corner_follows_the_closed_form_over_the_tributary_length) {
  // The same test with A tilted by 10 deg onto its corner: one vertex-edge
  // contact, whose tributary length is l_t = (w/2) cos 10 deg = 49.24 mm (the
  // projection on the joint of the longer-projecting half edge at the corner,
  // docs/reference/rheology-in-dda.md). The joint's shear displacement follows the
  // closed form at the stress tau_c = F2 / l_t = tau w / l_t within 0.5 % at
  // every step, every row of Table 1, implicit and exponential-linear; the
  // joint set's counters say one contact crept for the whole run.
  const double tilt = deg(10.0), lt = 0.5 * CreepScene::w * std::cos(tilt);
  for (const Table1Row& row : kTable1)
    for (laws::Scheme scheme : {laws::Scheme::implicit, laws::Scheme::exponential_linear}) {
      BOOST_TEST_CONTEXT("tau " << row.tau << " " << laws::scheme_name(scheme)) {
        auto law = table1_burgers(row);
        CreepScene scene(law, row.sigma, row.tau, 2.0, tilt);
        const double tau_c = row.tau * CreepScene::w / lt;
        contact::ContactSettings settings = core::contact_settings_for(scene.model);
        settings.scheme = scheme;
        contact::ContactSystem contacts({scene.joint}, settings);
        core::ContactAdapter adapter(contacts);
        core::Engine engine(scene.model, adapter);
        double worst = 0.0, d = 0.0, turn = 0.0;
        while (engine.time() < 200.0 - 1e-9) {
          // A's rotation at the start of the step [rad] (the tributary length
          // is measured on the step-start geometry).
          const auto& A = engine.block(1).map_A;
          turn = std::atan2(A(1, 0) - A(0, 1), A(0, 0) + A(1, 1));
          engine.step();
          BOOST_TEST_REQUIRE(contacts.contacts().size() == 1u);
          const contact::Contact& c = contacts.contacts()[0];
          BOOST_TEST_REQUIRE((c.kind == contact::ContactKind::vertex_edge));
          BOOST_TEST_REQUIRE((c.state == contact::ContactState::locked));
          d = joint_shear(contacts);
          const double e = law->displacement_closed_form(tau_c, engine.time());
          worst = std::max(worst, std::abs(d - e) / e);
        }
        const contact::Contact& c = contacts.contacts()[0];
        BOOST_TEST_MESSAGE("tilted onto a corner, Table 1 tau = "
                           << row.tau << " MPa, " << laws::scheme_name(scheme) << ": l_t = "
                           << c.tributary_length << " mm (A turned by " << turn
                           << " rad), d(" << engine.time() << " h) = " << d
                           << " mm (closed form "
                           << law->displacement_closed_form(tau_c, engine.time())
                           << "), max relative error " << worst);
        BOOST_TEST(worst < 0.005);
        // l_t follows the corner's tilt, tilt + turn.
        BOOST_TEST(c.tributary_length == 0.5 * CreepScene::w * std::cos(tilt + turn),
                   boost::test_tools::tolerance(1e-9));
        BOOST_TEST(contacts.creep_counters()[0].contacts == 1);
        // One contact, locked in every accepted step: its contact-time is the run's time.
        BOOST_TEST(contacts.creep_counters()[0].contact_time == engine.time(),
                   boost::test_tools::tolerance(1e-9));
      }
    }
}

BOOST_AUTO_TEST_CASE(a_block_rocking_from_its_keel_onto_either_face_keeps_a_continuous_creep_history) {
  // The engine's version of the rocking test (tests/contact/rheology_coupling_test.cpp):
  // A is a pentagon with a shallow keel, K = (50, 0), faces K-R to R = (100, 5)
  // and L-K from L = (0, 5) (5.7 deg, beyond the 3 deg angle tolerance), on
  // the fixed B; F1 and F2 of Table 1 row 1 act at K. It stands on K
  // (vertex_edge) until a clockwise couple (vertical loads -/+P at the top
  // corners, P = F1/10) tips it onto its right face over 20-22 h (K becomes
  // edge_edge, R carries 2P), then the reversed couple over 60-62 h tips it
  // back over K onto its left face (K: vertex_edge, then edge_edge again).
  // K's contact stays the same contact, locked, creeping in every step; its
  // creep displacement is the law's history (never reset) and grows in every
  // step (no jump back, no freeze).
  const Table1Row& row = kTable1[0];
  auto law = table1_burgers(row);
  CreepScene scene(law, row.sigma, row.tau, 2.0);
  core::Model& m = scene.model;
  const double w = CreepScene::w, F1 = row.sigma * w, P = 0.1 * F1;
  m.blocks[1] = block({{50.0, 0.0}, {100.0, 5.0}, {100.0, 105.0}, {0.0, 105.0}, {0.0, 5.0}});
  m.point_loads[0].point = m.point_loads[1].point = {50.0, 0.0};
  const std::vector<core::LoadSample> up = {{0.0, {0.0, 0.0}},  {20.0, {0.0, 0.0}}, {22.0, {0.0, P}},
                                            {60.0, {0.0, P}},   {62.0, {0.0, -P}},  {100.0, {0.0, -P}}};
  std::vector<core::LoadSample> down = up;
  for (auto& sample : down) sample.force = -sample.force;
  m.point_loads.push_back({1, {0.0, 105.0}, up});
  m.point_loads.push_back({1, {100.0, 105.0}, down});
  contact::ContactSettings settings = core::contact_settings_for(m);
  settings.scheme = laws::Scheme::implicit;
  contact::ContactSystem contacts({scene.joint}, settings);
  core::ContactAdapter adapter(contacts);
  core::Engine engine(m, adapter);
  const contact::ContactKey keel{1, 0, 0, 2};
  std::uint64_t id = 0;
  double last = 0.0;
  std::vector<contact::ContactKind> kinds;
  auto rotation = [&] {  // of A since the start, counter-clockwise [rad]
    const auto& A = engine.block(1).map_A;
    return std::atan2(A(1, 0) - A(0, 1), A(0, 0) + A(1, 1));
  };
  const double face = std::atan(5.0 / 50.0);  // a face lands after turning by this [rad]
  double on_right = 0.0;
  while (engine.time() < 100.0 - 1e-9) {
    engine.step();
    if (engine.time() <= 60.0) on_right = rotation();
    const contact::Contact* k = nullptr;
    for (const contact::Contact& c : contacts.contacts())
      if (c.key == keel) k = &c;
    BOOST_TEST_REQUIRE(k != nullptr);
    BOOST_TEST_CONTEXT("t = " << engine.time() << " h, " << contact::contact_kind_name(k->kind)) {
      if (id == 0) id = k->id;
      BOOST_TEST(k->id == id);
      BOOST_TEST_REQUIRE((k->state == contact::ContactState::locked));
      BOOST_TEST_REQUIRE(k->rheology >= 0);
      BOOST_TEST((k->creep_state == contact::CreepState::creeping));
      const double creep = -k->creep_displacement;  // along +x (B's top edge runs along -x)
      BOOST_TEST(k->creep_displacement == contacts.rheology_states()[k->rheology].creep(),
                 boost::test_tools::tolerance(1e-12));
      BOOST_TEST(creep > last);
      if (kinds.empty() || kinds.back() != k->kind) {
        BOOST_TEST_MESSAGE("t = " << engine.time() << " h: keel contact " << contact::contact_kind_name(k->kind)
                                  << ", l_t = " << k->tributary_length << " mm, creep " << creep << " mm");
        kinds.push_back(k->kind);
      }
      last = creep;
    }
  }
  using K = contact::ContactKind;
  BOOST_TEST((kinds == std::vector<K>{K::vertex_edge, K::edge_edge, K::vertex_edge, K::edge_edge}));
  BOOST_TEST_MESSAGE("A turned by " << on_right << " rad at 60 h and " << rotation()
                                    << " rad at 100 h (faces at -/+" << face << ")");
  BOOST_TEST(std::abs(on_right + face) < 0.01 * face);    // on its right face
  BOOST_TEST(std::abs(rotation() - face) < 0.01 * face);  // on its left face
}

BOOST_AUTO_TEST_CASE(maxwell_kelvin_and_nishihara_joints_follow_their_closed_forms) {
  // Same scene, 0-200 h, dt = 2 h, both accurate schemes. Kelvin has no
  // instantaneous spring: the joint's shear_stiffness k_s gives tau/k_s.
  // Nishihara below its threshold (no viscoplastic creep) and above it.
  const Table1Row& r = kTable1[0];
  for (const LawCase& c : other_law_cases())
    for (laws::Scheme scheme : {laws::Scheme::implicit, laws::Scheme::exponential_linear}) {
      BOOST_TEST_CONTEXT(c.name << " " << laws::scheme_name(scheme)) {
        auto law = make_law(c.law, c.p);
        CreepScene scene(law, r.sigma, r.tau, 2.0);
        scene.joint.shear_stiffness = c.shear_stiffness;
        const double elastic = c.shear_stiffness ? r.tau / *c.shear_stiffness : 0.0;
        double d200 = 0.0;
        const double worst = creep_error(
            scene, scheme, 200.0,
            [&](double t) { return elastic + law->displacement_closed_form(r.tau, t); }, &d200);
        BOOST_TEST_MESSAGE(c.name << " " << laws::scheme_name(scheme) << ": d(200 h) = " << d200
                                  << " mm, max relative error " << worst);
        BOOST_TEST(worst < 0.005);
      }
    }
}

BOOST_AUTO_TEST_CASE(implicit_creep_stays_accurate_at_a_thousand_times_the_lagged_limit) {
  // A stiff joint (E1 = 1e4 MPa/mm, Kelvin and dashpot of Table 1 row 1):
  // lagged limit dt* = 2 eta2/(E1 + E2) = 0.42 h. The implicit scheme at
  // 1000 dt* = 420 h follows the closed form to 0.5 % over 10 steps.
  const Table1Row& r = kTable1[0];
  auto law = make_law("burgers", {{"E1", 1e4}, {"E2", r.E2}, {"eta1", r.eta1}, {"eta2", r.eta2}});
  const double limit = 2 * r.eta2 / (1e4 + r.E2);
  CreepScene scene(law, r.sigma, r.tau, 1000 * limit);
  const double worst =
      creep_error(scene, laws::Scheme::implicit, 10000 * limit,
                  [&](double t) { return law->displacement_closed_form(r.tau, t); });
  BOOST_TEST_MESSAGE("implicit at 1000 dt* = " << 1000 * limit << " h: max relative error " << worst);
  BOOST_TEST(worst < 0.005);
}

BOOST_AUTO_TEST_CASE(ramped_load_converges_at_first_order_implicit_and_second_order_exponential_linear) {
  // F2 ramps from 0 to tau w over 0-50 h, then holds (F1 constant); Table 1
  // row 1. Closed form by superposition of ramp responses,
  //   R(t) = t/E1 + [t - eta2/E2 (1 - exp(-E2 t/eta2))]/E2 + t^2/(2 eta1)   (per unit stress rate),
  //   d(t) = (tau/T) [R(t) - R(t - T)]  (second term for t > T).
  // Largest error over the steps relative to d(200 h), at dt = 5 h and
  // 2.5 h: the ratio is 2 for the implicit scheme (1st order) and 4 for
  // exponential-linear (2nd order): measured orders within 0.2 and 0.4.
  const Table1Row& r = kTable1[0];
  auto law = table1_burgers(r);
  const double T = 50.0;
  auto R = [&](double t) {
    if (t <= 0.0) return 0.0;
    return t / r.E1 + (t - r.eta2 / r.E2 * -std::expm1(-r.E2 * t / r.eta2)) / r.E2 +
           t * t / (2 * r.eta1);
  };
  auto exact = [&](double t) { return r.tau / T * (R(t) - R(t - T)); };
  auto error = [&](laws::Scheme scheme, double dt) {
    CreepScene scene(law, r.sigma, r.tau, dt);
    scene.model.point_loads[1].history = {{0.0, {0.0, 0.0}}, {T, {r.tau * CreepScene::w, 0.0}}};
    return creep_error(scene, scheme, 200.0, exact, nullptr, exact(200.0));
  };
  for (laws::Scheme scheme : {laws::Scheme::implicit, laws::Scheme::exponential_linear}) {
    const double coarse = error(scheme, 5.0), fine = error(scheme, 2.5);
    const double order = std::log2(coarse / fine);
    BOOST_TEST_MESSAGE("ramp, " << laws::scheme_name(scheme) << ": max relative error "
                                << coarse << " (dt = 5 h), " << fine << " (dt = 2.5 h), order "
                                << order);
    BOOST_TEST_CONTEXT(laws::scheme_name(scheme)) {
      if (scheme == laws::Scheme::implicit) BOOST_TEST(std::abs(order - 1.0) < 0.2);
      else BOOST_TEST(std::abs(order - 2.0) < 0.4);
      BOOST_TEST(fine < 0.005);
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()
