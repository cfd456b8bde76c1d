// Engine::edit (docs/reference/stages.md): excavating blocks from a settled model gives
// the state of the model built without them; removed blocks lose their
// contacts and never get new ones; friction lowered between two steps makes a
// block on an incline slide from then on by the closed form; a fixed point
// added between two steps holds its block; a static analysis switched to
// dynamic; a bolt installed between two steps where its ends stand; invalid
// edits refused with the model unchanged; an edited run restored from its state
// steps on bit for bit.
#include <boost/test/unit_test.hpp>

#include "rheodda/laws/registry.hpp"
#include "sim.hpp"

using namespace rheodda;
using namespace rheodda::testing;

namespace {

/// A fixed base [-2, 2] x [-1, 0] and four 1 x 0.5 blocks: a, b on it 0.5 apart,
/// c on a, d on b (indices 1..4). Static analysis (dynamic_ratio 0),
/// E = 1e10 Pa, rho = 2600 kg/m^3, dt = 1 ms. `without_d`: block d left out.
core::Model stack(bool without_d) {
  core::Model m;
  m.settings.dynamic_ratio = 0.0;
  m.settings.dt = 1e-3;
  m.settings.open_close_limit = 30;
  add_fixed(m, rect(-2.0, -1.0, 2.0, 0.0));
  m.blocks.push_back(block(rect(-1.25, 0.0, -0.25, 0.5)));
  m.blocks.push_back(block(rect(0.25, 0.0, 1.25, 0.5)));
  m.blocks.push_back(block(rect(-1.25, 0.5, -0.25, 1.0)));
  if (!without_d) m.blocks.push_back(block(rect(0.25, 0.5, 1.25, 1.0)));
  return m;
}

/// A ModelEdit set up by `set` (the tests give only the fields they use).
template <class F>
core::ModelEdit edit_of(F set) {
  core::ModelEdit e;
  set(e);
  return e;
}

bool touches(const contact::Contact& c, int b) { return c.key.vblock == b || c.key.eblock == b; }

/// Fixed base whose top is the line through the origin at angle alpha, and a
/// 1 x 0.5 block resting on it, its lower corner 4 m up the slope.
core::Model incline(double alpha, double dynamic_ratio) {
  core::Model m;
  m.settings.dt = 1e-3;
  m.settings.dynamic_ratio = dynamic_ratio;
  add_fixed(m, rect(-1.0, -1.0, 7.0, 0.0, alpha));
  m.blocks.push_back(block(rect(4.0, 0.0, 5.0, 0.5, alpha)));
  return m;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(model_edit)

BOOST_AUTO_TEST_CASE(excavating_a_block_from_a_settled_stack_gives_the_stack_built_without_it) {
  // Settle the stack under gravity to t = 0.1 s, remove d, settle to 0.3 s;
  // compare with the stack built without d run to 0.3 s. No contact slides
  // (phi = 40 deg) or opens, so the springs are linear and the equilibrium does
  // not depend on the path: measured, the two agree to 5e-9 (displacements)
  // and 4e-9 (stresses) relative, below what halving the reference's step
  // changes (2.5e-7, 6e-9); asserted at 1e-6. (With a and b side by side,
  // touching, their side contact slid under d's load and did not slide back:
  // 2e-3, the path dependence of friction, not of the excavation.)
  const double t_cut = 0.1, t_end = 0.3;
  Sim dug(stack(false), {joint(40.0)});
  dug.engine.run_until(t_cut);
  const Vec2 d_before = dug.engine.centroid(4);
  const core::EditReport rep = dug.engine.edit(edit_of([&](core::ModelEdit& e) { e.remove_blocks = {4}; }));
  BOOST_TEST(rep.contacts_dropped > 0);
  for (const contact::Contact& c : dug.contacts.contacts()) BOOST_TEST(!touches(c, 4));
  dug.engine.run_until(t_end);
  for (const contact::Contact& c : dug.contacts.contacts()) BOOST_TEST(!touches(c, 4));
  BOOST_TEST(dug.engine.removed(4));
  BOOST_TEST((dug.engine.centroid(4) - d_before).norm() == 0.0);
  BOOST_TEST(dug.engine.stress(4).norm() == 0.0);

  Sim ref(stack(true), {joint(40.0)});
  ref.engine.run_until(t_end);
  core::Model fine_model = stack(true);
  fine_model.settings.dt = 0.5e-3;
  Sim fine(std::move(fine_model), {joint(40.0)});
  fine.engine.run_until(t_end);

  double u_scale = 0.0, s_scale = 0.0, du = 0.0, ds = 0.0, du_fine = 0.0, ds_fine = 0.0;
  for (int b = 1; b <= 3; ++b) {
    const Vec2 c0 = stack(true).blocks[b].vertices[0];
    const Vec2 u_ref = ref.engine.point_displacement(b, c0);
    u_scale = std::max(u_scale, u_ref.norm());
    s_scale = std::max(s_scale, ref.engine.stress(b).norm());
    du = std::max(du, (dug.engine.point_displacement(b, c0) - u_ref).norm());
    ds = std::max(ds, (dug.engine.stress(b) - ref.engine.stress(b)).norm());
    du_fine = std::max(du_fine, (fine.engine.point_displacement(b, c0) - u_ref).norm());
    ds_fine = std::max(ds_fine, (fine.engine.stress(b) - ref.engine.stress(b)).norm());
  }
  BOOST_TEST(dug.contacts.penalty() == ref.contacts.penalty());
  BOOST_TEST_MESSAGE("excavated vs built without: displacement "
                     << du / u_scale << ", stress " << ds / s_scale
                     << " (relative); reference dt vs dt/2: " << du_fine / u_scale << ", " << ds_fine / s_scale);
  BOOST_TEST(u_scale > 0.0);
  BOOST_TEST(s_scale > 10e3);  // a's vertical stress ~ rho g 0.75 m ~ 19 kPa
  BOOST_TEST(du <= 1e-6 * u_scale);
  BOOST_TEST(ds <= 1e-6 * s_scale);
}

BOOST_AUTO_TEST_CASE(a_block_falls_through_where_a_removed_block_stood) {
  // Dynamic: a (1 x 0.5) rests on the base, b hangs 0.1 m above it at rest.
  // a is removed at t = 0: b falls freely the 0.6 m to the base (y = -g t^2 / 2
  // until t = sqrt(2 0.6 / g) = 0.35 s) and lands on it, never touching a.
  core::Model m;
  m.settings.dt = 1e-3;
  add_fixed(m, rect(-2.0, -1.0, 2.0, 0.0));
  m.blocks.push_back(block(rect(-0.5, 0.0, 0.5, 0.5)));
  m.blocks.push_back(block(rect(-0.5, 0.6, 0.5, 1.1)));
  Sim sim(std::move(m), {joint(30.0)});
  sim.engine.edit(edit_of([&](core::ModelEdit& e) { e.remove_blocks = {1}; }));
  const double g = 9.81;
  double fall_error = 0.0, lowest = 1e9;  // b's lowest vertex over the run [m]
  while (sim.engine.time() < 0.6 - 1e-9) {
    sim.engine.step();
    for (const Vec2& v : sim.engine.vertices(2)) lowest = std::min(lowest, v.y());
    for (const contact::Contact& c : sim.contacts.contacts()) BOOST_TEST(!touches(c, 1));
    const double t = sim.engine.time();
    if (t < 0.3) fall_error = std::max(fall_error, std::abs(sim.engine.point_displacement(2, Vec2(0.0, 0.85)).y() +
                                                            0.5 * g * t * t));
  }
  BOOST_TEST_MESSAGE("free fall error to 0.3 s: " << fall_error << " m; b's lowest vertex over the run: " << lowest
                                                  << " m");
  BOOST_TEST(fall_error < 1e-9);  // Shi's scheme is exact for a constant acceleration
  // It reached the base (y = 0, a's bottom), not a's top (0.5 m), and did not pass through it.
  BOOST_TEST(std::abs(lowest) < 1e-3);
}

BOOST_AUTO_TEST_CASE(a_bolt_on_an_excavated_block_goes_with_it_and_the_block_below_carries_the_rest) {
  // Block c (3) hangs on a bolt to an anchor above it, its weight shared with a below;
  // removing c removes the bolt (docs/reference/stages.md): it carries nothing from
  // then on, and a carries its own weight again (N = rho g A_a).
  core::Model m = stack(true);
  core::Bolt bolt;
  bolt.block_a = 3;
  bolt.point_a = {-0.75, 1.0};
  bolt.block_b = -1;
  bolt.point_b = {-0.75, 2.0};
  bolt.axial_stiffness = 1e8;  // [N/m]
  bolt.pretension = 2000.0;    // [N]: part of c's 12 753 N/m weight
  m.bolts.push_back(bolt);
  Sim sim(m, {joint(30.0)});
  sim.engine.run_until(0.05);
  BOOST_TEST(sim.engine.bolts()[0].force > 1000.0);
  const core::EditReport rep = sim.engine.edit(edit_of([](core::ModelEdit& e) { e.remove_blocks = {3}; }));
  BOOST_TEST(rep.bolts_removed == std::vector<int>{0}, boost::test_tools::per_element());
  BOOST_TEST((sim.engine.bolts()[0].state == core::BoltMode::ruptured));
  sim.engine.run_until(0.1);
  BOOST_TEST(sim.engine.bolts()[0].force == 0.0);
  double n = 0.0;  // a's base contacts [N/m]
  for (const contact::Contact& c : sim.contacts.contacts())
    if (c.key.vblock == 1 && c.key.eblock == 0) n += std::abs(c.normal_force);
    else if (c.key.vblock == 0 && c.key.eblock == 1) n += std::abs(c.normal_force);
  const double weight = 2600.0 * 9.81 * 0.5;  // a: 1 m x 0.5 m [N/m]
  BOOST_TEST(std::abs(n - weight) < 1e-3 * weight, "N = " << n << ", rho g A = " << weight);
}

BOOST_AUTO_TEST_CASE(lowered_friction_makes_a_held_block_slide_by_the_closed_form) {
  // Dynamic analysis, alpha = 30 deg: phi = 40 deg holds the block until
  // t0 = 0.2 s; phi = 20 deg from then on: x = g (sin a - cos a tan phi) (t - t0)^2 / 2,
  // within 1 % after 1 m (the incline test's tolerance for a slide from rest).
  const double alpha = deg(30.0), g = 9.81, t0 = 0.2;
  Sim sim(incline(alpha, 1.0), {joint(40.0)});
  sim.engine.run_until(t0);
  const Vec2 c0 = sim.engine.block(1).centroid;
  const Vec2 down(-std::cos(alpha), -std::sin(alpha));
  BOOST_TEST(sim.engine.point_displacement(1, sim.engine.centroid(1)).norm() < 1e-4);
  sim.engine.edit(edit_of([&](core::ModelEdit& e) { e.joint_sets = {{0, joint(20.0)}}; }));
  BOOST_TEST(sim.contacts.joint_sets()[0].friction_angle == 20.0);
  double travelled = 0.0;
  while (travelled < 1.0 && sim.engine.step_count() < 5000) {
    sim.engine.step();
    travelled = (sim.engine.centroid(1) - c0).dot(down);
  }
  const double t = sim.engine.time() - t0;
  const double closed_form = 0.5 * g * (std::sin(alpha) - std::cos(alpha) * std::tan(deg(20.0))) * t * t;
  BOOST_TEST_MESSAGE("phi 40 -> 20 deg at " << t0 << " s: after " << t << " s DDA " << travelled << " m, closed form "
                                            << closed_form << " m");
  BOOST_TEST(travelled == closed_form, boost::test_tools::tolerance(0.01));
}

BOOST_AUTO_TEST_CASE(a_static_analysis_switched_to_dynamic_slides_by_the_closed_form) {
  // Static until t0 = 0.05 s with phi = 40 deg (the block stands), then
  // dynamic (dynamic_ratio 1) with phi = 20 deg: the slide from rest, 1 %.
  const double alpha = deg(30.0), g = 9.81, t0 = 0.05;
  Sim sim(incline(alpha, 0.0), {joint(40.0)});
  sim.engine.run_until(t0);
  const Vec2 c0 = sim.engine.centroid(1);
  const Vec2 down(-std::cos(alpha), -std::sin(alpha));
  sim.engine.edit(edit_of([&](core::ModelEdit& e) {
    e.joint_sets = {{0, joint(20.0)}};
    e.dynamic_ratio = 1.0;
  }));
  double travelled = 0.0;
  while (travelled < 1.0 && sim.engine.step_count() < 5000) {
    sim.engine.step();
    travelled = (sim.engine.centroid(1) - c0).dot(down);
  }
  const double t = sim.engine.time() - t0;
  const double closed_form = 0.5 * g * (std::sin(alpha) - std::cos(alpha) * std::tan(deg(20.0))) * t * t;
  BOOST_TEST_MESSAGE("static -> dynamic at " << t0 << " s: after " << t << " s DDA " << travelled << " m, closed form "
                                             << closed_form << " m");
  BOOST_TEST(travelled == closed_form, boost::test_tools::tolerance(0.01));
}

BOOST_AUTO_TEST_CASE(fixed_points_added_to_a_sliding_block_hold_it_where_it_is) {
  // The block slides (phi 20 deg on 30 deg, dynamic) until t0 = 0.3 s, then
  // two fixed points at its lower corners hold those material points where
  // they stand: over the next 0.5 s they move by less than the spring's give
  // (fixed_point_stiffness 100 E = 1e12 N/m per point, about m v / sqrt(k m) at
  // the catch, v ~ 0.8 m/s: ~1e-4 m), while the free slide goes 0.5 m on.
  const double alpha = deg(30.0), t0 = 0.3;
  Sim sim(incline(alpha, 1.0), {joint(20.0)});
  sim.engine.run_until(t0);
  const auto v = sim.engine.vertices(1);
  const Vec2 p0 = v[0], p1 = v[1];
  const double slid = sim.engine.point_displacement(1, incline(alpha, 1.0).blocks[1].vertices[0]).norm();
  BOOST_TEST(slid > 0.05);  // g (sin a - cos a tan phi) t0^2 / 2 = 0.082 m
  sim.engine.edit(edit_of([&](core::ModelEdit& e) { e.add_fixed_points = {{1, p0}, {1, p1}}; }));
  BOOST_TEST(sim.engine.model().fixed_points.size() == 5u);
  double worst = 0.0;
  while (sim.engine.time() < t0 + 0.5) {
    sim.engine.step();
    const auto w = sim.engine.vertices(1);
    worst = std::max({worst, (w[0] - p0).norm(), (w[1] - p1).norm()});
  }
  BOOST_TEST_MESSAGE("held corners moved at most " << worst << " m after the fixed points were added");
  BOOST_TEST(worst < 1e-3);
}

BOOST_AUTO_TEST_CASE(invalid_edits_are_refused_with_the_model_unchanged) {
  Sim sim(stack(false), {joint(40.0)});
  sim.engine.run(5);
  auto refused = [&](const core::ModelEdit& e, const std::string& key) {
    try {
      sim.engine.edit(e);
      BOOST_ERROR("edit accepted; expected refusal at " << key);
    } catch (const core::ModelError& err) {
      BOOST_TEST_MESSAGE(err.what());
      BOOST_TEST(err.key() == key);
    }
    BOOST_TEST(sim.engine.removed_blocks().empty());
    BOOST_TEST(sim.engine.model().fixed_points.size() == 3u);
  };
  refused(edit_of([&](core::ModelEdit& e) { e.remove_blocks = {7}; }), "remove_blocks[0]");
  refused(edit_of([&](core::ModelEdit& e) { e.remove_blocks = {2, 2}; }), "remove_blocks[1]");
  // The only fixed block: no support left.
  refused(edit_of([&](core::ModelEdit& e) { e.remove_blocks = {0}; }), "remove_blocks");
  refused(edit_of([&](core::ModelEdit& e) { e.remove_fixed_points = {0, 1, 2}; }), "remove_fixed_points");
  refused(edit_of([&](core::ModelEdit& e) { e.remove_fixed_points = {3}; }), "remove_fixed_points[0]");
  refused(edit_of([&](core::ModelEdit& e) { e.remove_point_loads = {0}; }), "remove_point_loads[0]");
  refused(edit_of([&](core::ModelEdit& e) { e.remove_blocks = {0, 1, 2, 3, 4}; }), "remove_blocks");
  refused(edit_of([&](core::ModelEdit& e) {
            e.add_fixed_points = {{1, Vec2(5.0, 5.0)}};
          }),
          "add_fixed_points[0].point");
  refused(edit_of([&](core::ModelEdit& e) { e.settle = true; }), "settle");
  // A bolt: an end off its block where the block stands, both ends on one block, no stiffness.
  auto bolt = [](int a, Vec2 pa, int b, Vec2 pb, double k) {
    core::Bolt x;
    x.block_a = a, x.point_a = pa, x.block_b = b, x.point_b = pb, x.axial_stiffness = k;
    return x;
  };
  refused(edit_of([&](core::ModelEdit& e) { e.add_bolts = {bolt(3, {-0.75, 3.0}, -1, {-0.75, 4.0}, 1e8)}; }),
          "add_bolts[0].a.point");
  refused(edit_of([&](core::ModelEdit& e) { e.add_bolts = {bolt(3, {-0.75, 0.9}, 3, {-0.75, 0.6}, 1e8)}; }),
          "add_bolts[0].block_b");
  refused(edit_of([&](core::ModelEdit& e) { e.add_bolts = {bolt(3, {-0.75, 0.9}, -1, {-0.75, 2.0}, 0.0)}; }),
          "add_bolts[0].axial_stiffness");
  BOOST_TEST(sim.engine.model().bolts.empty());
  sim.engine.edit(edit_of([&](core::ModelEdit& e) { e.remove_blocks = {4}; }));
  try {
    sim.engine.edit(edit_of([&](core::ModelEdit& e) { e.remove_blocks = {4}; }));
    BOOST_ERROR("a removed block removed again");
  } catch (const core::ModelError& err) {
    BOOST_TEST(err.key() == "remove_blocks[0]");
  }
}

BOOST_AUTO_TEST_CASE(an_edited_run_restored_from_its_state_steps_on_bit_for_bit) {
  // The edit is model, not state: a run resumed from a state saved after an
  // edit builds the engine, applies the same edit, then restores the state.
  Sim a(stack(false), {joint(40.0)});
  a.engine.run(20);
  const core::ModelEdit change = edit_of([&](core::ModelEdit& e) {
    e.remove_blocks = {4};
    e.add_fixed_points = {{1, Vec2(-0.5, 0.25)}};
    core::Bolt tie;  // c to b, across the gap, installed where they stand now (pretensioned)
    tie.block_a = 3, tie.point_a = {-0.3, 0.75}, tie.block_b = 2, tie.point_b = {0.3, 0.25};
    tie.axial_stiffness = 1e8, tie.pretension = 500.0;
    e.add_bolts = {tie};
  });
  const core::EditReport rep = a.engine.edit(change);
  a.engine.run(5);
  Sim b(stack(false), {joint(40.0)});
  b.engine.edit(rep.replay);
  b.engine.restore(a.engine.save());
  b.contacts.restore(a.contacts.state());
  a.engine.run(10);
  b.engine.run(10);
  for (int k = 0; k < a.engine.block_count(); ++k)
    for (std::size_t i = 0; i < a.engine.vertices(k).size(); ++i)
      BOOST_TEST((a.engine.vertices(k)[i] - b.engine.vertices(k)[i]).norm() == 0.0);
  BOOST_TEST_REQUIRE(b.engine.bolts().size() == 1u);
  BOOST_TEST(a.engine.bolts()[0].force == b.engine.bolts()[0].force);
  BOOST_TEST(rep.replay.add_bolts.at(0).installed_length == std::hypot(0.6, 0.5));
}

BOOST_AUTO_TEST_CASE(a_bolt_added_between_steps_is_installed_where_its_ends_stand) {
  // Block c (3) rests on a; a bolt from c to an anchor above it, installed after 50 steps
  // with pretension P: its force is P there, whatever c has settled before (bolt.hpp,
  // installed_length); c then presses on a with W - P (W = rho g A_c).
  Sim sim(stack(true), {joint(30.0)});
  sim.engine.run_until(0.05);
  const core::Vec2 p_now = sim.engine.point_position(3, {-0.75, 1.0});
  BOOST_TEST(p_now.y() < 1.0 - 1e-7, "c has not come down before the bolt: y = " << p_now.y());
  core::Bolt bolt;
  bolt.block_a = 3, bolt.point_a = p_now, bolt.block_b = -1, bolt.point_b = {-0.75, 2.0};
  bolt.axial_stiffness = 1e8, bolt.pretension = 2000.0;  // [N/m], [N/m]
  const double energy_before = sim.engine.energy().stored.bolt;
  sim.engine.edit(edit_of([&](core::ModelEdit& e) { e.add_bolts = {bolt}; }));
  BOOST_TEST_REQUIRE(sim.engine.bolts().size() == 1u);
  BOOST_TEST(sim.engine.bolts()[0].force == 2000.0);
  BOOST_TEST(std::abs(sim.engine.bolts()[0].length - (2.0 - p_now.y())) < 1e-15);  // |p_b - p_a| to round-off
  const double pretension_energy = 2000.0 * 2000.0 / (2.0 * 1e8);  // P^2 / 2k [N m/m]
  BOOST_TEST(std::abs(sim.engine.energy().stored.bolt - energy_before - pretension_energy) < 1e-15);
  const core::Vec2 material = sim.engine.model().bolts[0].point_a;  // the inverse of c's map, to round-off
  BOOST_TEST((material - core::Vec2(-0.75, 1.0)).norm() < 1e-14, "its end is c's material point at (-0.75, 1)");
  sim.engine.run_until(0.1);
  double n = 0.0;  // c on a [N/m]
  for (const contact::Contact& c : sim.contacts.contacts())
    if ((c.key.vblock == 3 && c.key.eblock == 1) || (c.key.vblock == 1 && c.key.eblock == 3)) n += std::abs(c.normal_force);
  const double w = 2600.0 * 9.81 * 0.5, f = sim.engine.bolts()[0].force;  // c: 1 m x 0.5 m [N/m]
  BOOST_TEST(std::abs(f - 2000.0) < 1e-2 * 2000.0, "N = " << f << " N/m: the bolt barely stretches");
  BOOST_TEST(std::abs(n - (w - f)) < 1e-3 * w, "c on a: " << n << " N/m, W - N = " << w - f);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(joint_set_edit)

BOOST_AUTO_TEST_CASE(a_joint_set_law_changes_its_parameters_but_is_not_added_removed_or_replaced) {
  const auto& registry = laws::LawRegistry::builtin();
  contact::JointSet j = joint(30.0);
  j.law = registry.create("burgers", {{"E1", 1e9}, {"E2", 2e9}, {"eta1", 3e12}, {"eta2", 4e10}});
  Sim sim(stack(false), {j});
  sim.engine.run(3);
  contact::JointSet slower = j;
  slower.law = registry.create("burgers", {{"E1", 1e9}, {"E2", 2e9}, {"eta1", 6e12}, {"eta2", 4e10}});
  sim.engine.edit(edit_of([&](core::ModelEdit& e) { e.joint_sets = {{0, slower}}; }));
  BOOST_TEST(sim.contacts.joint_sets()[0].law->parameters().at("eta1") == 6e12);
  sim.engine.run(3);
  contact::JointSet none = j;
  none.law = nullptr;
  BOOST_CHECK_THROW(sim.engine.edit(edit_of([&](core::ModelEdit& e) {
    e.joint_sets = {{0, none}};
  })),
                    std::invalid_argument);
  contact::JointSet renamed = slower;
  renamed.name = "other";
  BOOST_CHECK_THROW(sim.engine.edit(edit_of([&](core::ModelEdit& e) {
    e.joint_sets = {{0, renamed}};
  })),
                    std::invalid_argument);
  contact::JointSet steep = slower;
  steep.friction_angle = 95.0;  // checked as the constructor checks it
  BOOST_CHECK_THROW(sim.engine.edit(edit_of([&](core::ModelEdit& e) {
    e.joint_sets = {{0, steep}};
  })),
                    std::invalid_argument);
  BOOST_TEST(sim.contacts.joint_sets()[0].friction_angle == 30.0);
}

BOOST_AUTO_TEST_SUITE_END()
