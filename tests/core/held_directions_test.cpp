// Fixed points held in one direction, and the velocity of a block that fixed points
// begin or stop holding (core/src/held_velocity.hpp; docs/reference/engine.md, "Fixing
// and freeing a moving block"): closed forms of Shi's scheme, exact for a constant
// acceleration (free_fall_test.cpp).
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "rheodda/core/engine.hpp"
#include "test_support.hpp"

using namespace rheodda::core;
using rheodda::core::test::block;

namespace {

constexpr double kG = 9.81;

/// A 1 m square falling freely (dynamic, dt 0.01 s), moving at vx in x from the start.
Model falling_square(double vx) {
  Model m;
  m.settings.dt = 0.01;
  m.settings.g2 = 1.0;
  m.settings.dynamic_ratio = 1.0;
  m.settings.gravity = {0.0, -kG};
  m.blocks.push_back(block({{0, 0}, {1, 0}, {1, 1}, {0, 1}}));
  m.blocks.back().initial_velocity = {vx, 0.0};
  return m;
}

/// Stored energy now minus at t = 0, less the net input and the summed residual: zero
/// when every change of the stored energy is booked [force x length].
double unbooked(const EnergyBalance& e) {
  return (e.stored.total() - e.initial.total()) - e.total.net_input() - e.total.residual;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(held_directions)

BOOST_AUTO_TEST_CASE(a_block_held_in_x_at_its_centroid_falls_freely_and_does_not_move_in_x) {
  Model m = falling_square(0.0);
  FixedPoint fp{.block = 0, .point = {0.5, 0.5}};
  fp.hold_y = false;
  m.fixed_points.push_back(fp);
  Engine e(m);
  e.run(50);
  const Vec2 d = e.point_displacement(0, {0.5, 0.5});
  BOOST_TEST(std::abs(d.y() + kG * 0.25 / 2) <= 1e-12);  // g t^2 / 2 at t = 0.5 s
  BOOST_TEST(std::abs(d.x()) <= 1e-15);
}

BOOST_AUTO_TEST_CASE(fixing_a_falling_block_in_y_stops_its_fall_and_books_that_kinetic_energy) {
  // At t1 a point held in y at the centroid: the y velocity g t1 goes (its kinetic energy
  // m (g t1)^2 / 2 booked as dissipation_edits), the x velocity stays.
  const double vx = 0.5, t1 = 0.3;
  Engine e(falling_square(vx));
  e.run(30);
  const double mass = Material{}.density * 1.0;
  ModelEdit edit;
  FixedPoint fp{.block = 0, .point = e.centroid(0)};
  fp.hold_x = false;
  edit.add_fixed_points.push_back(fp);
  const EditReport r = e.edit(edit);
  BOOST_TEST(std::abs(e.velocity(0)(0) - vx) <= 1e-12);
  BOOST_TEST(e.velocity(0)(1) == 0.0);
  const double taken = mass * (kG * t1) * (kG * t1) / 2;
  BOOST_TEST(std::abs(r.kinetic_energy_taken - taken) <= 1e-12 * taken);
  BOOST_TEST(std::abs(e.energy().total.dissipation_edits - taken) <= 1e-12 * taken);
  e.run(20);
  BOOST_TEST(std::abs(e.point_displacement(0, {0.5, 0.5}).x() - vx * 0.5) <= 1e-12);
  BOOST_TEST(std::abs(unbooked(e.energy())) <= 1e-9 * taken);
}

BOOST_AUTO_TEST_CASE(a_block_fixed_at_every_vertex_stops_and_a_freed_one_starts_from_rest) {
  // A second block, fixed and far away, keeps the model held once the first is freed.
  Model m = falling_square(0.5);
  m.blocks.push_back(block({{5, 0}, {6, 0}, {6, 1}, {5, 1}}));
  m.fixed_points.push_back({.block = 1, .point = {5, 0}});
  m.fixed_points.push_back({.block = 1, .point = {6, 0}});
  Engine e(m);
  e.run(30);
  ModelEdit fix;
  for (const Vec2& v : e.vertices(0)) fix.add_fixed_points.push_back({.block = 0, .point = v});
  e.edit(fix);
  BOOST_TEST(e.velocity(0).norm() == 0.0);
  e.run(7);  // an odd number of held steps: the springs' vibration is there now
  ModelEdit free;
  free.remove_fixed_points = {2, 3, 4, 5};
  const double springs = e.energy().stored.fixed;
  e.edit(free);
  // The removed springs' energy leaves the balance at the edit (docs/reference/stages.md, "Energy").
  const double removed = springs - e.energy().stored.fixed;
  BOOST_TEST(e.velocity(0).norm() == 0.0);
  const Vec2 at_free = e.point_displacement(0, {0.5, 0.5});
  e.run(40);
  const Vec2 d = e.point_displacement(0, {0.5, 0.5}) - at_free;
  BOOST_TEST(std::abs(d.y() + kG * 0.16 / 2) <= 1e-12);  // g t^2 / 2 from rest, t = 0.4 s
  BOOST_TEST(std::abs(d.x()) <= 1e-12);
  BOOST_TEST(std::abs(unbooked(e.energy()) + removed) <= 1e-9 * Material{}.density * kG);
}

BOOST_AUTO_TEST_CASE(a_velocity_set_is_checked_and_booked) {
  Engine e(falling_square(0.0));
  e.run(10);
  const double mass = Material{}.density * 1.0;
  const double before = e.energy().stored.kinetic;
  ModelEdit edit;
  Vec6 v = Vec6::Zero();
  v(0) = 2.0;
  edit.set_velocities.emplace_back(0, v);
  const EditReport r = e.edit(edit);
  BOOST_TEST(std::abs(r.kinetic_energy_taken - (before - mass * 4.0 / 2)) <= 1e-12 * mass);
  e.run(10);
  BOOST_TEST(std::abs(e.velocity(0)(0) - 2.0) <= 1e-12);
  BOOST_TEST(std::abs(unbooked(e.energy())) <= 1e-9 * mass);
  // Refused: not finite, a removed or unknown block, a held direction, a static analysis.
  ModelEdit bad;
  bad.set_velocities.emplace_back(3, v);
  BOOST_CHECK_THROW(e.edit(bad), ModelError);
  ModelEdit hold;
  hold.add_fixed_points.push_back({.block = 0, .point = e.centroid(0)});
  hold.set_velocities.emplace_back(0, v);
  try {
    e.edit(hold);
    BOOST_ERROR("a velocity moving a held point was accepted");
  } catch (const ModelError& err) {
    BOOST_TEST(err.key() == "set_velocities[0].velocity");
  }
  ModelEdit to_static;
  to_static.dynamic_ratio = 0.0;
  to_static.set_velocities.emplace_back(0, v);
  BOOST_CHECK_THROW(e.edit(to_static), ModelError);
}

BOOST_AUTO_TEST_SUITE_END()
