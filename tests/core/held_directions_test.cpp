// Fixed points held in one direction, blocks held in rotation (FixedPoint::hold_rotation,
// core/src/block_terms.hpp, RotationHold), and the velocity of a block that fixed points
// begin or stop holding (core/src/held_velocity.hpp; docs/reference/engine.md, "Fixing
// and freeing a moving block", "Holding a block's rotation"): closed forms of Shi's scheme,
// exact for a constant acceleration (free_fall_test.cpp), and of the rotational spring
// k_r = p J/S.
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "rheodda/core/defaults.hpp"
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
  m.settings.max_displacement_ratio = 1.0;
  m.settings.dynamic_ratio = 1.0;
  m.settings.gravity = {0.0, -kG};
  m.blocks.push_back(block({{0, 0}, {1, 0}, {1, 1}, {0, 1}}));
  m.blocks.back().initial_velocity = {vx, 0.0};
  return m;
}

/// A W x H rectangle [m] with its lower-left corner at (x, y).
std::vector<Vec2> rectangle(double x, double y, double W, double H) {
  return {{x, y}, {x + W, y}, {x + W, y + H}, {x, y + H}};
}

/// A fixed point at p on block b holding the block's rotation only.
FixedPoint rotation_hold(int b, const Vec2& p) {
  FixedPoint fp{.block = b, .point = p};
  fp.hold_x = fp.hold_y = false;
  fp.hold_rotation = true;
  return fp;
}

/// The mean rotation of a block whose initial shape is an axis-parallel W x H rectangle
/// (block_terms.hpp, RotationHold): the angle of F Sigma0, Sigma0 = diag(W^2, H^2) S/12 [rad].
double mean_rotation(const Engine& e, int b, double W, double H) {
  const Mat2 A = e.block(b).map_A * Eigen::Vector2d(W * W, H * H).asDiagonal();
  return std::atan2(A(1, 0) - A(0, 1), A(0, 0) + A(1, 1));
}

/// The polar angle of a block's affine map F = R U (Block.rotation) [rad].
double polar_rotation(const Engine& e, int b) {
  const Mat2& F = e.block(b).map_A;
  return std::atan2(F(1, 0) - F(0, 1), F(0, 0) + F(1, 1));
}

/// The automatic fixed-point spring p = 100 E of the default material [N/m per m].
double penalty() { return default_fixed_point_stiffness(Material{}.young_modulus); }

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

BOOST_AUTO_TEST_CASE(a_block_held_in_rotation_alone_is_pushed_off_centre_as_a_free_mass_without_turning) {
  // A 1 m square in the air, no gravity, pushed by F in x at the middle of its top edge
  // (h = 0.5 m above the centroid: a torque -h F) and held in rotation only. Its centroid
  // moves F t^2/(2 m) (Shi's scheme is exact for a constant force); its rotation is the
  // torque over the rotational spring, -h F / k_r, k_r = p J/S = p/6 [N m/rad per m], and
  // would be -h F t^2/(2 I) = -1.44 rad at t = 0.5 s without the hold.
  for (const Integrator integrator : {Integrator::implicit, Integrator::explicit_step}) {
    Model m = falling_square(0.0);
    m.settings.gravity = {0.0, 0.0};
    m.settings.integrator = integrator;
    m.settings.explicit_damping = 0.0;  // the cycles undamped: the rotation swings within [0, 2 M/k_r]
    const double F = 1.0e4, h = 0.5;    // [N/m], [m]
    m.point_loads.push_back({.block = 0, .point = {0.5, 0.5 + h}, .history = {{0.0, {F, 0.0}}}});
    m.fixed_points.push_back(rotation_hold(0, {0.5, 0.5}));
    Engine e(m);
    const double mass = Material{}.density * 1.0, k_r = penalty() / 6.0, torque = -h * F;
    if (integrator == Integrator::explicit_step) {
      // The stable cycle at the rotational spring's frequency, sqrt(k_r / (rho J)) = sqrt(p/m)
      // [1/s], above the square's strain modes (sqrt(6.2e7) 1/s): explicit_safety x 2/omega.
      const Engine::StableCycle c = e.stable_cycle();
      BOOST_TEST(c.block == 0);
      BOOST_TEST(c.cycle == 0.8 * 2.0 / std::sqrt(penalty() / mass), boost::test_tools::tolerance(1e-9));
      BOOST_TEST(e.block_cycles() == std::vector<double>{c.cycle}, boost::test_tools::per_element());
    }
    e.run(50);
    const double t = 0.5;
    const Vec2 d = e.point_displacement(0, {0.5, 0.5});
    BOOST_TEST_MESSAGE((integrator == Integrator::implicit ? "implicit" : "explicit")
                       << ": x " << d.x() << " m (F t^2/(2m) " << F * t * t / (2 * mass) << "), rotation "
                       << polar_rotation(e, 0) << " rad (M/k_r " << torque / k_r << ")");
    BOOST_TEST(d.x() == F * t * t / (2 * mass), boost::test_tools::tolerance(1e-9));
    BOOST_TEST(std::abs(d.y()) <= 1e-9 * d.x());
    if (integrator == Integrator::implicit) {  // Shi's scheme at omega dt = 196: the static deflection
      BOOST_TEST(polar_rotation(e, 0) == torque / k_r, boost::test_tools::tolerance(1e-3));
      // The spring's energy M^2/(2 k_r) in energy_fixed, every change booked.
      BOOST_TEST(e.energy().stored.fixed == torque * torque / (2 * k_r), boost::test_tools::tolerance(2e-3));
      BOOST_TEST(std::abs(unbooked(e.energy())) <= 1e-9 * e.energy().total.work_loads);
    } else {
      BOOST_TEST((polar_rotation(e, 0) / (torque / k_r) >= -1e-9 && polar_rotation(e, 0) / (torque / k_r) <= 2.0));
    }
  }
}

BOOST_AUTO_TEST_CASE(a_held_rotation_deflects_by_the_torque_over_p_J_over_S) {
  // A 2 m x 1 m block (static) held at its centroid in x, y and rotation (one fixed point),
  // turned by a pure torque M = 1 MN m/m (x forces -+f on the top and bottom edges, y forces
  // +-g on the right and left, f = M/(4 h), g = h f / h': no load on the strains). The spring
  // on its mean rotation balances it: theta = M / k_r, k_r = p J/S = p (W^2 + H^2)/12, and
  // stores M^2 / (2 k_r).
  const double W = 2.0, H = 1.0, M = 1.0e6, h = 0.5, hp = 1.0;
  const double f = M / (4.0 * h), g = h * f / hp;
  Model m;
  m.settings.dt = 0.01;
  m.settings.dynamic_ratio = 0.0;
  m.settings.gravity = {0.0, 0.0};
  m.blocks.push_back(block(rectangle(0.0, 0.0, W, H)));
  FixedPoint fp{.block = 0, .point = {1.0, 0.5}};
  fp.hold_rotation = true;
  m.fixed_points.push_back(fp);
  m.point_loads.push_back({.block = 0, .point = {1.0, 1.0}, .history = {{0.0, {-f, 0.0}}}});
  m.point_loads.push_back({.block = 0, .point = {1.0, 0.0}, .history = {{0.0, {f, 0.0}}}});
  m.point_loads.push_back({.block = 0, .point = {2.0, 0.5}, .history = {{0.0, {0.0, g}}}});
  m.point_loads.push_back({.block = 0, .point = {0.0, 0.5}, .history = {{0.0, {0.0, -g}}}});
  Engine e(m);
  e.run(5);
  const double k_r = penalty() * (W * W + H * H) / 12.0;
  BOOST_TEST(k_r == rotation_hold_stiffness(penalty(), m.blocks[0].vertices), boost::test_tools::tolerance(1e-14));
  const double theta = mean_rotation(e, 0, W, H);
  BOOST_TEST_MESSAGE("theta " << theta << " rad, M/k_r " << M / k_r << " rad; Block.rotation " << polar_rotation(e, 0));
  BOOST_TEST(theta == M / k_r, boost::test_tools::tolerance(1e-8));
  BOOST_TEST(e.energy().stored.fixed == M * M / (2.0 * k_r), boost::test_tools::tolerance(1e-7));
  BOOST_TEST(e.point_displacement(0, {1.0, 0.5}).norm() <= 1e-6 * theta);  // no net force on the point
}

BOOST_AUTO_TEST_CASE(a_spinning_block_held_in_rotation_stops_turning_and_books_half_I_omega_squared) {
  // A block falling at vx = 0.5 m/s and spinning at omega = 2 rad/s is held in rotation at
  // t1 = 0.3 s: its angular velocity goes (rho J omega^2/2 booked as dissipation_edits,
  // whatever its shape), its fall and slide go on, and it is held at the rotation it had
  // then (0.6 rad), not the initial one.
  for (const double H : {1.0, 0.5}) {
    const double vx = 0.5, omega = 2.0, W = 1.0;
    Model m = falling_square(vx);
    m.blocks[0] = block(rectangle(0.0, 0.0, W, H));
    m.blocks[0].initial_velocity = {vx, 0.0};
    m.blocks[0].initial_angular_velocity = omega;
    Engine e(m);
    e.run(30);
    const double turned = mean_rotation(e, 0, W, H);
    BOOST_TEST(turned == omega * 0.3, boost::test_tools::tolerance(1e-12));
    const Vec6 before = e.velocity(0);
    ModelEdit edit;
    edit.add_fixed_points.push_back(rotation_hold(0, e.centroid(0)));
    const EditReport r = e.edit(edit);
    BOOST_TEST(r.replay.add_fixed_points[0].held_rotation.value() == turned, boost::test_tools::tolerance(1e-15));
    const Vec6 v = e.velocity(0);
    BOOST_TEST(std::abs(v(2)) <= 1e-12 * omega);
    BOOST_TEST(v(0) == before(0), boost::test_tools::tolerance(1e-14));  // the projection's round-off
    BOOST_TEST(v(1) == before(1), boost::test_tools::tolerance(1e-14));
    BOOST_TEST(v.tail<3>().norm() <= 1e-12 * omega * W);
    const double I = Material{}.density * (W * W * W * H + W * H * H * H) / 12.0;  // rho J [kg m^2/m]
    BOOST_TEST_MESSAGE("H " << H << ": taken " << r.kinetic_energy_taken << " J/m, I omega^2/2 "
                            << 0.5 * I * omega * omega);
    BOOST_TEST(r.kinetic_energy_taken == 0.5 * I * omega * omega, boost::test_tools::tolerance(1e-12));
    BOOST_TEST(e.energy().total.dissipation_edits == 0.5 * I * omega * omega, boost::test_tools::tolerance(1e-12));
    e.run(20);
    BOOST_TEST(std::abs(mean_rotation(e, 0, W, H) - turned) <= 1e-9);
    const Vec2 d = e.point_displacement(0, {0.5 * W, 0.5 * H});
    BOOST_TEST(d.x() == vx * 0.5, boost::test_tools::tolerance(1e-9));
    BOOST_TEST(d.y() == -kG * 0.25 / 2, boost::test_tools::tolerance(1e-9));
    BOOST_TEST(std::abs(unbooked(e.energy())) <= 1e-9 * I * omega * omega);
  }
}

BOOST_AUTO_TEST_CASE(a_rotation_hold_is_checked) {
  Model m = falling_square(0.0);
  FixedPoint none{.block = 0, .point = {0.5, 0.5}};
  none.hold_x = none.hold_y = false;
  m.fixed_points.push_back(none);
  try {
    Engine e(m);
    BOOST_ERROR("a fixed point holding nothing was accepted");
  } catch (const ModelError& err) {
    BOOST_TEST(err.key() == "fixed_points[0].hold");
    BOOST_TEST(err.message() == "holds nothing (neither x, y nor the rotation)");
  }
  Engine e(falling_square(0.0));
  ModelEdit replay;
  replay.material_points = true;
  replay.add_fixed_points.push_back(rotation_hold(0, {0.5, 0.5}));
  replay.add_fixed_points[0].material_point = Vec2(0.5, 0.5);
  BOOST_CHECK_THROW(e.edit(replay), ModelError);  // a replay names the rotation held
  replay.add_fixed_points[0].held_rotation = 0.25;
  e.edit(replay);
  BOOST_TEST(e.model().fixed_points[0].held_rotation.value() == 0.25);
}

BOOST_AUTO_TEST_SUITE_END()
