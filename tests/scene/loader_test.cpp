// The scene loader: valid scenes are read with every default filled in; every
// class of bad input is refused with the file, line, column and key of the fault.
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "test_support.hpp"
#include "rheodda/scene/build.hpp"
#include "rheodda/scene/describe.hpp"
#include "rheodda/scene/geometry.hpp"
#include "rheodda/scene/loader.hpp"

using namespace rheodda;
using namespace rheodda::test;

BOOST_AUTO_TEST_SUITE(scene_loader)

BOOST_AUTO_TEST_CASE(base_scene_loads_with_documented_defaults) {
  const scene::SceneDescription s = scene::parse_scene(kBaseScene, "base.yaml");
  BOOST_TEST(s.units.length == "m");
  BOOST_TEST(s.units.stress() == "N/m^2");
  BOOST_TEST((s.analysis.type == scene::AnalysisType::static_analysis));
  BOOST_TEST(s.analysis.dynamic_ratio == 0.0);
  BOOST_TEST(!s.analysis.scheme.has_value());  // automatic
  BOOST_TEST(s.analysis.max_displacement_ratio == 0.01);
  BOOST_TEST(s.analysis.output_interval == 0.01);     // duration / 100
  BOOST_TEST(s.analysis.penalty == 40.0 * 1.0e9);      // 40 x largest young_modulus
  BOOST_TEST(s.analysis.fixed_point_stiffness == 100.0 * 1.0e9);
  BOOST_TEST(s.analysis.open_close_limit == 8);  // static: Shi's limit (the next test: 30 in dynamic analysis)
  BOOST_TEST(s.analysis.max_cuts == 30);
  BOOST_TEST((s.materials[0].plane == core::PlaneMode::plane_strain));
  BOOST_TEST(s.joint_sets.size() == 2u);
  BOOST_TEST(s.joint_sets[0].cohesion == 0.0);
  BOOST_TEST(!s.joint_sets[0].normal_stiffness.has_value());
  BOOST_TEST(!s.joint_sets[0].law.has_value());
  BOOST_TEST(s.joint_sets[1].law->name == "burgers");
  BOOST_TEST(s.joint_sets[1].law->parameters.at("eta2") == 4.0);
  BOOST_TEST(s.blocks.size() == 2u);
  BOOST_TEST(s.blocks[0].fixed);
  BOOST_TEST((s.blocks[0].edge_joint_set == std::vector<int>{0, 0, 0, 0}));
  BOOST_TEST((s.blocks[1].edge_joint_set == std::vector<int>{1, 0, 0, 0}));
  BOOST_TEST(s.measurement_points[0].at.block == 1);  // (1.5, 1.5) lies in `top` only
}

BOOST_AUTO_TEST_CASE(clockwise_polygon_is_reversed_and_edge_joint_sets_follow_their_edges) {
  // Clockwise square with the fault on the edge (1,2)->(2,2) (the top edge).
  const auto text = with("polygon: [[1, 1], [2, 1], [2, 2], [1, 2]], edge_joint_sets: [fault, bedding, bedding, bedding]",
                         "polygon: [[1, 1], [1, 2], [2, 2], [2, 1]], edge_joint_sets: [bedding, fault, bedding, bedding]");
  const auto s = scene::parse_scene(text, "cw.yaml");
  const auto& b = s.blocks[1];
  BOOST_TEST(scene::signed_area(b.polygon) > 0.0);
  for (std::size_t k = 0; k < b.polygon.size(); ++k) {
    const auto& p = b.polygon[k];
    const auto& q = b.polygon[(k + 1) % b.polygon.size()];
    const bool top_edge = p[1] == 2.0 && q[1] == 2.0;
    BOOST_TEST(b.edge_joint_set[k] == (top_edge ? 1 : 0), "edge " << k);
  }
}

BOOST_AUTO_TEST_CASE(rectangle_grid_and_angle_shorthands_expand_to_polygons) {
  const auto text = with("  - {name: top, polygon: [[1, 1], [2, 1], [2, 2], [1, 2]], edge_joint_sets: [fault, bedding, bedding, bedding]}\n",
                         "  - {name: wall, grid: {x: 0, y: 1, width: 1, height: 0.5, columns: 3, rows: 2}, joint_set: bedding}\n"
                         "  - {name: tilted, rectangle: {x: 3.5, y: 1, width: 0.5, height: 0.2, angle: 90}, joint_set: fault}\n");
  const auto s = scene::parse_scene(with("[1.5, 1.5]", "[1.5, 1.25]", text), "grid.yaml");
  BOOST_TEST(s.blocks.size() == 8u);
  BOOST_TEST(s.blocks[1].name == "wall.r1.c1");
  BOOST_TEST(s.blocks[6].name == "wall.r2.c3");
  BOOST_TEST(s.blocks[6].polygon[0][0] == 2.0);
  BOOST_TEST(s.blocks[6].polygon[0][1] == 1.5);
  const auto& t = s.blocks[7];  // rotated 90 deg about (3.5, 1): width along +y
  BOOST_TEST(t.polygon[1][0] == 3.5, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(t.polygon[1][1] == 1.5, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(scene::signed_area(t.polygon) == 0.1, boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(a_fixed_point_holding_the_rotation_is_read_built_described_and_checked) {
  // `hold: rotation` on the 1 m square `top`: the engine's point holds its rotation alone, with
  // the spring p J/S = 1e11/6 N m/rad (fixed_point_stiffness 100 E); several entries combine.
  const std::string points = "fixed_points:\n  - {point: [1.5, 1.5], block: top, hold: rotation}\n"
                             "  - {point: [1.5, 1.5], block: top, hold: x}\nmeasurement_points:\n";
  const auto s = scene::parse_scene(with("measurement_points:\n", points), "hold.yaml");
  BOOST_TEST(s.fixed_points[0].hold == "rotation");
  const auto built = scene::build_scene(s);
  const auto& fixed = built.model.fixed_points;  // the base's four corners (fixed: true), then the entries
  BOOST_TEST_REQUIRE(fixed.size() == 6u);
  BOOST_TEST((fixed[4].hold_rotation && !fixed[4].hold_x && !fixed[4].hold_y));
  BOOST_TEST((fixed[5].hold_x && !fixed[5].hold_y && !fixed[5].hold_rotation));
  BOOST_TEST(scene::describe_scene(s).find("block top, hold rotation (a rotational spring of 1.667e+10 N·m/rad)") !=
             std::string::npos);
  expect_error_at(with("measurement_points:\n", "fixed_points:\n  - {point: [1.5, 1.5], hold: spin}\n"
                                                 "measurement_points:\n"),
                  15, "spin", "fixed_points[0].hold", "'spin' is not one of: both, x, y, rotation");
}

BOOST_AUTO_TEST_CASE(unknown_key_names_line_column_and_nearest_valid_key) {
  expect_error_at(with("  dt: 0.01", "  dtt: 0.01"), 4, "dtt", "analysis.dtt", "did you mean 'dt'?");
  expect_error_at(with("joint_sets:", "joint_set:"), 8, "joint_set", "joint_set", "did you mean 'joint_sets'?");
  expect_error_at(with("friction_angle: 30", "friction_angel: 30"), 9, "friction", "joint_sets.bedding.friction_angel",
                  "did you mean 'friction_angle'?");
}

BOOST_AUTO_TEST_CASE(residual_strength_defaults_to_the_peak_friction_and_no_cohesion_and_is_at_most_the_peak) {
  // Default: the peak friction angle, no cohesion (what a contact kept before the keys
  // existed: results unchanged); given: read, and refused above the peak or below 0.
  const auto d = scene::parse_scene(kBaseScene, "base.yaml");
  BOOST_TEST(!d.joint_sets[0].residual_friction_angle.has_value());
  BOOST_TEST(d.joint_sets[0].residual_cohesion == 0.0);
  const auto b = scene::build_scene(d);
  BOOST_TEST(b.joint_sets[0].friction_angle_of(false) == 30.0);
  BOOST_TEST(b.joint_sets[0].cohesion_of(false) == 0.0);
  const std::string given = with("{friction_angle: 30}",
                                 "{friction_angle: 30, cohesion: 5, residual_friction_angle: 22, residual_cohesion: 1}");
  const auto g = scene::build_scene(scene::parse_scene(given, "base.yaml"));
  BOOST_TEST(g.joint_sets[0].friction_angle_of(true) == 30.0);
  BOOST_TEST(g.joint_sets[0].friction_angle_of(false) == 22.0);
  BOOST_TEST(g.joint_sets[0].cohesion_of(true) == 5.0);
  BOOST_TEST(g.joint_sets[0].cohesion_of(false) == 1.0);
  BOOST_TEST(scene::describe_scene(scene::parse_scene(given, "base.yaml")).find(
                 "residual_friction_angle 22 deg, residual_cohesion 1 N/m^2") != std::string::npos);
  expect_error_at(with("{friction_angle: 30}", "{friction_angle: 30, residual_friction_angle: 31}"), 9, "31",
                  "joint_sets.bedding.residual_friction_angle", "above the peak friction_angle 30 deg");
  expect_error_at(with("{friction_angle: 30}", "{friction_angle: 30, residual_friction_angle: -1}"), 9, "-1",
                  "joint_sets.bedding.residual_friction_angle", "out of range");
  expect_error_at(with("{friction_angle: 30}", "{friction_angle: 30, cohesion: 2, residual_cohesion: 3}"), 9, "3}",
                  "joint_sets.bedding.residual_cohesion", "above the peak cohesion 2");
  expect_error_at(with("{friction_angle: 30}", "{friction_angle: 30, residual_cohesion: .nan}"), 9, ".nan",
                  "joint_sets.bedding.residual_cohesion", "not a finite number");
}

BOOST_AUTO_TEST_CASE(law_parameters_use_the_registry_names) {
  expect_error_at(with("eta1: 3", "eta_1: 3"), 10, "eta_1", "joint_sets.fault.law.eta_1", "did you mean 'eta1'?");
  expect_error_at(with("name: burgers", "name: burger"), 10, "burger", "law.name", "did you mean 'burgers'?");
  expect_error_at(with(", eta2: 4}", "}"), 10, "{name", "law.eta2", "needs parameter 'eta2'");
}

BOOST_AUTO_TEST_CASE(a_law_with_E1_and_a_shear_stiffness_is_refused_as_giving_one_value_twice) {
  expect_error_at(with("fault: {friction_angle: 20,", "fault: {friction_angle: 20, shear_stiffness: 5,"), 10, "5,",
                  "joint_sets.fault.shear_stiffness", "sets the joint's elastic shear stiffness with its E1");
}

BOOST_AUTO_TEST_CASE(missing_required_key_points_at_its_map) {
  expect_error(with("  duration: 1\n", ""), 3, 3, "analysis.duration", "missing required key 'duration'");
  expect_error_at(with("density: 2600, ", ""), 7, "{young", "materials.rock.density", "missing required key 'density'");
  expect_error(with("units: {length: m, force: N, time: s}\n", ""), 1, 1, "units", "missing required key 'units'");
}

BOOST_AUTO_TEST_CASE(wrong_type_is_reported_at_the_value) {
  expect_error_at(with("  dt: 0.01", "  dt: fast"), 4, "fast", "analysis.dt", "'fast' is not a number");
  expect_error_at(with("gravity: [0, -9.81]", "gravity: 9.81"), 5, "9.81", "analysis.gravity", "list of 2 numbers");
  expect_error_at(with("fixed: true", "fixed: maybe"), 12, "maybe", "blocks[0].fixed", "not true or false");
  expect_error_at(with("  duration: 1", "  type: quasi\n  duration: 1"), 3, "quasi",
                  "analysis.type", "not one of: static, dynamic");
}

BOOST_AUTO_TEST_CASE(out_of_range_values_are_refused) {
  expect_error_at(with("eta1: 3", "eta1: -3"), 10, "-3", "law.eta1", "out of range");
  expect_error_at(with("friction_angle: 30", "friction_angle: 90"), 9, "90", "bedding.friction_angle", "out of range [0, 90)");
  expect_error_at(with("density: 2600", "density: 0"), 7, "0,", "materials.rock.density", "out of range (0, inf]");
  expect_error_at(with("poisson_ratio: 0.25", "poisson_ratio: 0.5"), 7, "0.5", "poisson_ratio", "out of range [0, 0.5)");
  expect_error_at(with("  dt: 0.01", "  dt: 2"), 4, "2", "analysis.dt", "longer than duration");
}

BOOST_AUTO_TEST_CASE(creep_tolerance_and_dt_max_reach_the_engine_settings_and_negative_values_are_refused) {
  const auto text = with("  dt: 0.01", "  dt: 0.01\n  creep_tolerance: 1.0e-6\n  dt_max: 0.5\n"
                                       "  creep_restart_on_contact_change: true");
  const scene::SceneDescription s = scene::parse_scene(text, "adaptive.yaml");
  BOOST_TEST(s.analysis.creep_tolerance == 1.0e-6);
  BOOST_TEST(s.analysis.dt_max == 0.5);
  const scene::BuiltScene built = scene::build_scene(s);
  BOOST_TEST(built.model.settings.creep_tolerance == 1.0e-6);
  BOOST_TEST(built.model.settings.dt_max == 0.5);
  BOOST_TEST(built.model.settings.creep_restart_on_contact_change);
  // Off by default: a fixed dt.
  BOOST_TEST(scene::build_scene(scene::parse_scene(kBaseScene, "base.yaml")).model.settings.creep_tolerance == 0.0);
  BOOST_TEST(!scene::build_scene(scene::parse_scene(kBaseScene, "base.yaml")).model.settings.creep_restart_on_contact_change);
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  creep_restart_on_contact_change: maybe"), 5, "maybe",
                  "analysis.creep_restart_on_contact_change", "is not true or false");
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  creep_tolerance: -1"), 5, "-1", "analysis.creep_tolerance",
                  "out of range");
}

BOOST_AUTO_TEST_CASE(a_settling_stage_reaches_the_engine_settings_and_bad_ones_are_refused) {
  // docs/reference/engine.md, "Settling stage".
  const auto text = with("  dt: 0.01", "  dt: 0.01\n  settle: {until: 0.1, dt: 0.001, max_displacement_ratio: 0.0005}");
  const scene::SceneDescription s = scene::parse_scene(text, "settle.yaml");
  BOOST_TEST_REQUIRE(s.analysis.has_settle());
  BOOST_TEST(s.analysis.settle.until == 0.1);
  BOOST_TEST(s.analysis.settle.dt == 0.001);
  BOOST_TEST(s.analysis.settle.max_displacement_ratio == 0.0005);
  const scene::BuiltScene built = scene::build_scene(s);
  BOOST_TEST(built.model.settings.settle.until == 0.1);
  BOOST_TEST(built.model.settings.settle.dt == 0.001);
  BOOST_TEST(built.model.settings.settle.max_displacement_ratio == 0.0005);
  // Its max_displacement_ratio defaults to the analysis's; no stage by default.
  BOOST_TEST(scene::parse_scene(with("  dt: 0.01", "  dt: 0.01\n  max_displacement_ratio: 0.002\n"
                                                   "  settle: {until: 0.1, dt: 0.001}"), "d.yaml")
                 .analysis.settle.max_displacement_ratio == 0.002);
  BOOST_TEST(scene::build_scene(scene::parse_scene(kBaseScene, "base.yaml")).model.settings.settle.until == 0.0);
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  settle: {until: 1, dt: 0.001}"), 5, "1,",
                  "analysis.settle.until", "not before the analysis does");
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  settle: {until: 0.1, dt: 0.5}"), 5, "0.5",
                  "analysis.settle.dt", "longer than the settling stage");
  expect_error(with("  dt: 0.01", "  dt: 0.01\n  settle: {until: 0.1}"), 5, 0, "analysis.settle.dt", "required");
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  settle: {until: 0.1, dt: 0.001, max_displacement_ratio: 0}"), 5,
                  "0}", "analysis.settle.max_displacement_ratio", "out of range");
}

BOOST_AUTO_TEST_CASE(a_dynamic_settling_stage_admits_the_damping_keys_in_a_static_analysis) {
  // docs/reference/engine.md, "Settling stage": `settle: {type: dynamic}` makes the
  // stage's steps carry velocity in a static analysis; the damping keys are
  // then accepted (they act in the stage), the stage keeps a sticking
  // contact's force unless the scene says otherwise, and its static steps
  // follow Shi's rule.
  const std::string stage = with("  dt: 0.01", "  dt: 0.01\n  settle: {until: 0.1, dt: 0.001, type: dynamic}");
  const auto s = scene::parse_scene(
      with("poisson_ratio: 0.25}", "poisson_ratio: 0.25, damping_ratio: 1}",
           with("bedding: {friction_angle: 30}", "bedding: {friction_angle: 30, restitution: 0}", stage)),
      "settle-dynamic.yaml");
  BOOST_TEST_REQUIRE(s.analysis.has_settle());
  BOOST_TEST(s.analysis.settle.dynamic);
  BOOST_TEST(s.analysis.has_dynamic_steps());
  const scene::BuiltScene built = scene::build_scene(s);
  BOOST_TEST(built.model.settings.settle.dynamic);
  BOOST_TEST(built.model.settings.dynamic_ratio == 0.0);
  BOOST_TEST(built.model.materials[0].damping_ratio == 1.0);
  BOOST_TEST(built.contact_settings.lock_at_touch);
  BOOST_TEST(!built.contact_settings.stick_keeps_force);
  BOOST_TEST_REQUIRE(built.contact_settings.stick_keeps_force_dynamic.has_value());
  BOOST_TEST(*built.contact_settings.stick_keeps_force_dynamic);
  BOOST_TEST(scene::describe_scene(s).find("settling stage (dynamic)") != std::string::npos);
  // A scene's own stick_keeps_force applies to every step.
  const auto given = scene::build_scene(scene::parse_scene(
      with("  dt: 0.01\n", "  dt: 0.01\n  stick_keeps_force: false\n", stage), "given.yaml"));
  BOOST_TEST(!given.contact_settings.stick_keeps_force_dynamic.has_value());
  // Without the stage's type the keys are refused, as in any static analysis.
  expect_error_at(with("bedding: {friction_angle: 30}", "bedding: {friction_angle: 30, restitution: 0}",
                       with("  dt: 0.01", "  dt: 0.01\n  settle: {until: 0.1, dt: 0.001}")),
                  10, "0}", "joint_sets.bedding.restitution", "or a dynamic settling stage");
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  settle: {until: 0.1, dt: 0.001, type: fast}"), 5, "fast",
                  "analysis.settle.type", "");
  // A dynamic analysis's stage is dynamic: `type: static` there is refused, not ignored.
  expect_error_at(with("  duration: 1\n", "  type: dynamic\n  duration: 1\n",
                       with("  dt: 0.01", "  dt: 0.01\n  settle: {until: 0.1, dt: 0.001, type: static}")),
                  6, "static", "analysis.settle.type", "is dynamic");
}

BOOST_AUTO_TEST_CASE(collapse_dt_reaches_the_engine_with_a_dynamic_stage_of_a_static_analysis_only) {
  // docs/reference/engine.md, "Collapse stages".
  const auto text = with("  dt: 0.01", "  dt: 0.01\n  settle: {until: 0.1, dt: 0.001, type: dynamic, collapse_dt: 0.002}");
  const auto s = scene::parse_scene(text, "collapse.yaml");
  BOOST_TEST_REQUIRE(s.analysis.has_settle());
  BOOST_TEST(s.analysis.settle.collapse_dt == 0.002);
  const scene::BuiltScene built = scene::build_scene(s);
  BOOST_TEST(built.model.settings.settle.collapse_dt == 0.002);
  // The static steps keep the stages' stick rule unless the scene gives one.
  BOOST_TEST(built.contact_settings.stick_keeps_force);
  BOOST_TEST(*built.contact_settings.stick_keeps_force_dynamic);
  const auto shi = scene::build_scene(scene::parse_scene(
      with("  dt: 0.01\n", "  dt: 0.01\n  stick_keeps_force: false\n", text), "shi.yaml"));
  BOOST_TEST(!shi.contact_settings.stick_keeps_force);
  BOOST_TEST(!shi.contact_settings.stick_keeps_force_dynamic.has_value());
  BOOST_TEST(scene::describe_scene(s).find("collapse stages") != std::string::npos);
  // Not with a static stage, not at or above dt, not with step doubling, not negative.
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  settle: {until: 0.1, dt: 0.001, collapse_dt: 0.002}"), 5,
                  "0.002}", "analysis.settle.collapse_dt", "give `type: dynamic`");
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  settle: {until: 0.1, dt: 0.001, type: dynamic, collapse_dt: 0.01}"),
                  5, "0.01}", "analysis.settle.collapse_dt", "not below the analysis's dt");
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  settle: {until: 0.1, dt: 0.001, type: dynamic, collapse_dt: -1}"),
                  5, "-1}", "analysis.settle.collapse_dt", "out of range");
  expect_error_at(with("  dt: 0.01\n", "  dt: 0.01\n  step_tolerance: 1.0e-4\n", text), 5, "1.0e-4",
                  "analysis.step_tolerance", "no collapse stage");
}

BOOST_AUTO_TEST_CASE(gravity_ramp_reaches_the_engine_and_must_end_within_the_settling_stage) {
  // docs/reference/engine.md, "Gravity ramp".
  const auto text = with("  dt: 0.01", "  dt: 0.01\n  settle: {until: 0.1, dt: 0.001, type: dynamic, gravity_ramp: 0.05}");
  const auto s = scene::parse_scene(text, "ramp.yaml");
  BOOST_TEST_REQUIRE(s.analysis.has_settle());
  BOOST_TEST(s.analysis.settle.gravity_ramp == 0.05);
  const scene::BuiltScene built = scene::build_scene(s);
  BOOST_TEST(built.model.settings.settle.gravity_ramp == 0.05);
  BOOST_TEST(built.model.settings.gravity_at(0.025).y() == 0.5 * built.model.settings.gravity.y());
  BOOST_TEST(built.model.settings.gravity_at(0.06).y() == built.model.settings.gravity.y());
  BOOST_TEST(scene::describe_scene(s).find("gravity ramp") != std::string::npos);
  // Without it gravity comes on at once.
  BOOST_TEST(scene::build_scene(scene::parse_scene(with("  dt: 0.01", "  dt: 0.01\n  settle: {until: 0.1, dt: 0.001}"),
                                                   "once.yaml"))
                 .model.settings.settle.gravity_ramp == 0.0);
  // Not beyond the stage, not zero or negative.
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  settle: {until: 0.1, dt: 0.001, gravity_ramp: 0.2}"), 5, "0.2}",
                  "analysis.settle.gravity_ramp", "after the settling stage");
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  settle: {until: 0.1, dt: 0.001, gravity_ramp: 0}"), 5, "0}",
                  "analysis.settle.gravity_ramp", "out of range");
}

BOOST_AUTO_TEST_CASE(rest_tolerance_ends_stages_at_rest_and_makes_until_their_longest) {
  // docs/reference/engine.md, "Dynamic stages".
  const auto text = with("  dt: 0.01", "  dt: 0.01\n  settle: {dt: 0.001, type: dynamic, rest_tolerance: 1.0e-5}");
  const auto s = scene::parse_scene(text, "rest.yaml");
  BOOST_TEST_REQUIRE(s.analysis.has_settle());
  BOOST_TEST(s.analysis.settle.rest_tolerance == 1e-5);
  BOOST_TEST(s.analysis.settle.until == s.analysis.duration);  // no length given: at most the duration
  const scene::BuiltScene built = scene::build_scene(s);
  BOOST_TEST(built.model.settings.settle.rest_tolerance == 1e-5);
  BOOST_TEST(built.model.settings.settle.until == s.analysis.duration);
  BOOST_TEST(scene::describe_scene(s).find("until at rest") != std::string::npos);
  // With `until`, it is the longest; without rest_tolerance `until` is still required.
  BOOST_TEST(scene::parse_scene(with("  dt: 0.01", "  dt: 0.01\n  settle: {until: 0.1, dt: 0.001, type: dynamic, "
                                                  "rest_tolerance: 1.0e-5}"),
                                "rest.yaml")
                 .analysis.settle.until == 0.1);
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  settle: {dt: 0.001, type: dynamic}"), 5, "{dt",
                  "analysis.settle.until", "required");
  // Only a dynamic stage comes to rest; a fraction in (0, 1).
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  settle: {dt: 0.001, rest_tolerance: 1.0e-5}"), 5, "1.0e-5}",
                  "analysis.settle.rest_tolerance", "give `type: dynamic`");
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  settle: {dt: 0.001, type: dynamic, rest_tolerance: 1}"), 5, "1}",
                  "analysis.settle.rest_tolerance", "out of range");
}

BOOST_AUTO_TEST_CASE(a_stage_takes_its_own_open_close_limit) {
  // docs/reference/engine.md, "Dynamic stages": the stage's steps are cut after this many
  // iterates; without it they take the analysis's (8 in a static analysis).
  const auto text = with("  dt: 0.01", "  dt: 0.01\n  settle: {until: 0.1, dt: 0.001, type: dynamic, open_close_limit: 30}");
  const auto s = scene::parse_scene(text, "limit.yaml");
  BOOST_TEST(s.analysis.settle.open_close_limit == 30);
  const scene::BuiltScene built = scene::build_scene(s);
  BOOST_TEST(built.model.settings.settle.open_close_limit == 30);
  BOOST_TEST(built.model.settings.open_close_limit == s.analysis.open_close_limit);
  BOOST_TEST(scene::describe_scene(s).find("cut after 30 open-close iterates") != std::string::npos);
  const auto plain = scene::parse_scene(with("  dt: 0.01", "  dt: 0.01\n  settle: {until: 0.1, dt: 0.001}"), "limit.yaml");
  BOOST_TEST(scene::build_scene(plain).model.settings.settle.open_close_limit == 0);
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  settle: {until: 0.1, dt: 0.001, open_close_limit: 0}"), 5, "0}",
                  "analysis.settle.open_close_limit", "out of range");
}

BOOST_AUTO_TEST_CASE(step_tolerance_and_step_extrapolation_reach_the_engine_settings_and_bad_values_are_refused) {
  const auto text = with("  dt: 0.01", "  dt: 0.01\n  step_tolerance: 1.0e-4\n  step_extrapolation: false\n"
                                       "  dt_max: 0.5");
  const scene::SceneDescription s = scene::parse_scene(text, "doubling.yaml");
  BOOST_TEST(s.analysis.step_tolerance == 1.0e-4);
  BOOST_TEST(!s.analysis.step_extrapolation);
  const scene::BuiltScene built = scene::build_scene(s);
  BOOST_TEST(built.model.settings.step_tolerance == 1.0e-4);
  BOOST_TEST(!built.model.settings.step_extrapolation);
  BOOST_TEST(built.model.settings.dt_max == 0.5);
  BOOST_TEST(built.model.settings.creep_tolerance == 0.0);
  // Off by default; extrapolation on by default under a tolerance.
  const scene::BuiltScene base = scene::build_scene(scene::parse_scene(kBaseScene, "base.yaml"));
  BOOST_TEST(base.model.settings.step_tolerance == 0.0);
  BOOST_TEST(scene::parse_scene(with("  dt: 0.01", "  dt: 0.01\n  step_tolerance: 1.0e-4"), "d.yaml")
                 .analysis.step_extrapolation);
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  step_tolerance: -1"), 5, "-1", "analysis.step_tolerance",
                  "out of range");
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  creep_tolerance: 1e-6\n  step_tolerance: 1e-4"), 6, "1e-4",
                  "analysis.step_tolerance", "not both");
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  step_extrapolation: true"), 5, "true",
                  "analysis.step_extrapolation", "under step_tolerance only");
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  step_tolerance: 1e-4\n  step_extrapolation: often"), 6,
                  "often", "analysis.step_extrapolation", "is not true or false");
  // dt_max: only with an adaptive control, and not below dt.
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  dt_max: 0.5"), 5, "0.5", "analysis.dt_max",
                  "under creep_tolerance or step_tolerance only");
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  step_tolerance: 1e-4\n  dt_max: 0.001"), 6, "0.001",
                  "analysis.dt_max", "shorter than dt");
}

BOOST_AUTO_TEST_CASE(solver_and_solver_tolerances_reach_the_engine_settings_and_bad_values_are_refused) {
  // Default: automatic with the iterative stop 1e-10.
  const scene::BuiltScene base = scene::build_scene(scene::parse_scene(kBaseScene, "base.yaml"));
  BOOST_TEST((base.model.settings.solver == core::SolverKind::automatic));
  BOOST_TEST(base.model.settings.solver_tolerance == 1e-10);
  const auto text = with("  dt: 0.01", "  dt: 0.01\n  solver: amg\n  solver_tolerance: 1.0e-8");
  const scene::BuiltScene built = scene::build_scene(scene::parse_scene(text, "amg.yaml"));
  BOOST_TEST((built.model.settings.solver == core::SolverKind::amg));
  BOOST_TEST(built.model.settings.solver_tolerance == 1e-8);
  for (auto [name, kind] : {std::pair{"cholmod", core::SolverKind::cholmod}, {"pcg", core::SolverKind::pcg},
                            {"automatic", core::SolverKind::automatic}}) {
    const auto t = with("  dt: 0.01", std::string("  dt: 0.01\n  solver: ") + name);
    BOOST_TEST((scene::build_scene(scene::parse_scene(t, "s.yaml")).model.settings.solver == kind));
  }
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  solver: lu"), 5, "lu", "analysis.solver",
                  "not one of: automatic, cholmod, pcg, amg");
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  solver_tolerance: 0"), 5, "0", "analysis.solver_tolerance",
                  "out of range (0, 1)");
  // The stop of iterates whose states still change: default 1e-4, 0 allowed (off).
  BOOST_TEST(base.model.settings.solver_iterate_tolerance == 1e-4);
  for (double v : {0.0, 1e-6}) {
    const auto t = with("  dt: 0.01", "  dt: 0.01\n  solver_iterate_tolerance: " + std::to_string(v));
    BOOST_TEST(scene::build_scene(scene::parse_scene(t, "s.yaml")).model.settings.solver_iterate_tolerance == v);
  }
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  solver_iterate_tolerance: 1"), 5, "1",
                  "analysis.solver_iterate_tolerance", "out of range [0, 1)");
}

BOOST_AUTO_TEST_CASE(time_integration_reaches_the_engine_settings_and_needs_a_dynamic_analysis) {
  // Default: Shi's scheme.
  const scene::SceneDescription base = scene::parse_scene(kBaseScene, "base.yaml");
  BOOST_TEST((base.analysis.time_integration == scene::TimeIntegration::shi));
  BOOST_TEST((scene::build_scene(base).model.settings.time_integration == core::TimeIntegration::shi));
  const auto dynamic = with("  dt: 0.01", "  dt: 0.01\n  type: dynamic\n  time_integration: trapezoidal");
  const scene::SceneDescription s = scene::parse_scene(dynamic, "trapezoidal.yaml");
  BOOST_TEST((s.analysis.time_integration == scene::TimeIntegration::trapezoidal));
  BOOST_TEST((scene::build_scene(s).model.settings.time_integration == core::TimeIntegration::trapezoidal));
  const auto shi = with("  dt: 0.01", "  dt: 0.01\n  type: dynamic\n  time_integration: shi");
  BOOST_TEST((scene::build_scene(scene::parse_scene(shi, "shi.yaml")).model.settings.time_integration ==
              core::TimeIntegration::shi));
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  time_integration: newmark"), 5, "newmark",
                  "analysis.time_integration", "'newmark' is not one of: shi, trapezoidal");
  // The engine would refuse these too (settings.time_integration), but only at
  // `run` and pointing at the analysis map: the loader names the key's line.
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  time_integration: trapezoidal"), 5, "trapezoidal",
                  "analysis.time_integration", "a static analysis carries no velocity");
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  type: dynamic\n  dynamic_ratio: 0\n  time_integration: trapezoidal"),
                  7, "trapezoidal", "analysis.time_integration", "dynamic_ratio = 0 carries no velocity");
}

BOOST_AUTO_TEST_CASE(the_explicit_step_keys_reach_the_engine_and_are_refused_where_they_do_nothing) {
  // docs/reference/explicit-step.md: integrator, explicit_safety, explicit_damping, stage_local_damping,
  // stage_cycles.
  const scene::SceneDescription base = scene::parse_scene(kBaseScene, "base.yaml");
  BOOST_TEST((scene::build_scene(base).model.settings.integrator == core::Integrator::implicit));
  const auto dynamic = with("  dt: 0.01", "  dt: 0.01\n  type: dynamic\n  integrator: explicit\n  explicit_safety: 0.8\n"
                                         "  explicit_damping: 0.25");
  const core::Settings st = scene::build_scene(scene::parse_scene(dynamic, "explicit.yaml")).model.settings;
  BOOST_TEST((st.integrator == core::Integrator::explicit_step));
  BOOST_TEST(st.explicit_safety == 0.8);
  BOOST_TEST(st.explicit_damping == 0.25);
  BOOST_TEST(st.stage_local_damping == 0.0);
  const auto stages = with("  dt: 0.01", "  dt: 0.01\n  integrator: explicit\n  stage_local_damping: 0.8\n"
                                        "  stage_cycles: 200\n"
                                        "  settle: {type: dynamic, until: 0.1, dt: 0.001, max_displacement_ratio: 0.001}");
  const core::Settings staged = scene::build_scene(scene::parse_scene(stages, "stages.yaml")).model.settings;
  BOOST_TEST(staged.stage_local_damping == 0.8);
  BOOST_TEST(staged.stage_cycles == 200);
  BOOST_TEST(st.stage_cycles == 0);
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  integrator: leapfrog"), 5, "leapfrog", "analysis.integrator",
                  "'leapfrog' is not one of: implicit, explicit");
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  integrator: explicit"), 5, "explicit", "analysis.integrator",
                  "a static analysis without a dynamic settling stage");
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  explicit_safety: 0.3"), 5, "0.3", "analysis.explicit_safety",
                  "give integrator: explicit");
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  type: dynamic\n  integrator: explicit\n  explicit_safety: 1.5"), 7,
                  "1.5", "analysis.explicit_safety", "out of range");
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  type: dynamic\n  integrator: explicit\n  stage_local_damping: 0.8"),
                  7, "0.8", "analysis.stage_local_damping", "a dynamic analysis never takes it");
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  type: dynamic\n  integrator: explicit\n  stage_cycles: 100"),
                  7, "100", "analysis.stage_cycles", "a dynamic analysis never takes it");
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  stage_cycles: 100"), 5, "100", "analysis.stage_cycles",
                  "give integrator: explicit");
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  type: dynamic\n  integrator: explicit\n  stage_cycles: -1"), 7,
                  "-1", "analysis.stage_cycles", "out of range");
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  type: dynamic\n  integrator: explicit\n  time_integration: trapezoidal"),
                  6, "explicit", "analysis.integrator", "central difference");
  // settle.force_ratio (docs/reference/explicit-step.md, "Rest by the unbalanced force").
  const auto ratio = with("  dt: 0.01", "  dt: 0.01\n  integrator: explicit\n"
                                       "  settle: {type: dynamic, dt: 0.001, rest_tolerance: 1.0e-5, force_ratio: 1.0e-5}");
  BOOST_TEST(scene::build_scene(scene::parse_scene(ratio, "ratio.yaml")).model.settings.settle.force_ratio == 1e-5);
  BOOST_TEST(staged.settle.force_ratio == 0.0);
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  integrator: explicit\n"
                                    "  settle: {type: dynamic, until: 0.1, dt: 0.001, force_ratio: 1.0e-5}"),
                  6, "1.0e-5", "analysis.settle.force_ratio", "give `rest_tolerance` too");
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  settle: {type: dynamic, dt: 0.001, rest_tolerance: 1.0e-5, "
                                    "force_ratio: 2.0e-5}"),
                  5, "2.0e-5", "analysis.settle.force_ratio", "give integrator: explicit or automatic");
}

BOOST_AUTO_TEST_CASE(open_close_limit_defaults_to_8_in_static_and_30_in_dynamic_analysis_and_reaches_the_engine) {
  // docs/notes/contact-solves.md, "The iteration limit in static analysis".
  BOOST_TEST(scene::build_scene(scene::parse_scene(kBaseScene, "base.yaml")).model.settings.open_close_limit == 8);
  const auto dynamic = with("  dt: 0.01", "  dt: 0.01\n  type: dynamic");
  BOOST_TEST(scene::build_scene(scene::parse_scene(dynamic, "dyn.yaml")).model.settings.open_close_limit == 30);
  const auto given = with("  dt: 0.01", "  dt: 0.01\n  open_close_limit: 30");
  BOOST_TEST(scene::build_scene(scene::parse_scene(given, "given.yaml")).model.settings.open_close_limit == 30);
  const auto given_dynamic = with("  dt: 0.01", "  dt: 0.01\n  type: dynamic\n  open_close_limit: 8");
  BOOST_TEST(scene::build_scene(scene::parse_scene(given_dynamic, "gd.yaml")).model.settings.open_close_limit == 8);
}

BOOST_AUTO_TEST_CASE(stick_keeps_force_reaches_the_contact_settings_default_on_only_in_dynamic_analysis) {
  // The base scene is static: Shi's rule by default; a dynamic scene keeps the force by default.
  BOOST_TEST(!scene::build_scene(scene::parse_scene(kBaseScene, "base.yaml")).contact_settings.stick_keeps_force);
  const auto on = with("  dt: 0.01", "  dt: 0.01\n  stick_keeps_force: true");
  BOOST_TEST(scene::build_scene(scene::parse_scene(on, "on.yaml")).contact_settings.stick_keeps_force);
  const auto dynamic = with("  dt: 0.01", "  dt: 0.01\n  type: dynamic");
  BOOST_TEST(scene::build_scene(scene::parse_scene(dynamic, "dyn.yaml")).contact_settings.stick_keeps_force);
  const auto dynamic_off = with("  dt: 0.01", "  dt: 0.01\n  type: dynamic\n  stick_keeps_force: false");
  BOOST_TEST(!scene::build_scene(scene::parse_scene(dynamic_off, "off.yaml")).contact_settings.stick_keeps_force);
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  stick_keeps_force: sometimes"), 5, "sometimes",
                  "analysis.stick_keeps_force", "is not true or false");
}

BOOST_AUTO_TEST_CASE(open_close_settings_reach_the_contact_settings_and_bad_values_are_refused) {
  // Defaults: the contact layer's (contact::ContactSettings).
  const contact::ContactSettings defaults;
  const contact::ContactSettings base =
      scene::build_scene(scene::parse_scene(kBaseScene, "base.yaml")).contact_settings;
  BOOST_TEST(base.friction_tolerance == defaults.friction_tolerance);
  BOOST_TEST(base.force_resolution == defaults.force_resolution);
  BOOST_TEST(base.max_flips == defaults.max_flips);
  BOOST_TEST(base.max_refinements == defaults.max_refinements);
  BOOST_TEST(base.penalty_raise == defaults.penalty_raise);
  BOOST_TEST(base.penalty_max_factor == defaults.penalty_max_factor);
  const auto set = with("  dt: 0.01", "  dt: 0.01\n  friction_tolerance: 0.05\n  force_resolution: 0.01\n"
                                      "  max_flips: 4\n  max_refinements: 0\n  penalty_raise: 1.5\n"
                                      "  penalty_max_factor: 8");
  const contact::ContactSettings cs = scene::build_scene(scene::parse_scene(set, "set.yaml")).contact_settings;
  BOOST_TEST(cs.friction_tolerance == 0.05);
  BOOST_TEST(cs.force_resolution == 0.01);
  BOOST_TEST(cs.max_flips == 4);
  BOOST_TEST(cs.max_refinements == 0);
  BOOST_TEST(cs.penalty_raise == 1.5);
  BOOST_TEST(cs.penalty_max_factor == 8.0);
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  force_resolution: 1"), 5, "1",
                  "analysis.force_resolution", "out of range [0, 1)");
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  max_flips: 0"), 5, "0", "analysis.max_flips", "out of range [1, 1000]");
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  friction_tolerance: 0"), 5, "0",
                  "analysis.friction_tolerance", "out of range");
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  penalty_raise: 0.5"), 5, "0.5", "analysis.penalty_raise", "out of range");
}

BOOST_AUTO_TEST_CASE(dt_growth_dt_cut_and_solver_max_iterations_reach_the_engine_settings_and_bad_values_are_refused) {
  // Defaults: the engine's (core::Settings).
  const core::Settings defaults;
  const core::Settings base = scene::build_scene(scene::parse_scene(kBaseScene, "base.yaml")).model.settings;
  BOOST_TEST(base.dt_growth == defaults.dt_growth);
  BOOST_TEST(base.dt_cut == defaults.dt_cut);
  BOOST_TEST(base.solver_max_iterations == defaults.solver_max_iterations);
  const auto text = with("  dt: 0.01", "  dt: 0.01\n  dt_growth: 1.2\n  dt_cut: 0.5\n  solver_max_iterations: 250");
  const scene::SceneDescription s = scene::parse_scene(text, "steps.yaml");
  BOOST_TEST(s.analysis.dt_growth == 1.2);
  BOOST_TEST(s.analysis.dt_cut == 0.5);
  BOOST_TEST(s.analysis.solver_max_iterations == 250);
  const core::Settings built = scene::build_scene(s).model.settings;
  BOOST_TEST(built.dt_growth == 1.2);
  BOOST_TEST(built.dt_cut == 0.5);
  BOOST_TEST(built.solver_max_iterations == 250);
  // dt_growth = 1 (the step stays cut) is allowed; below 1 it would shrink steps.
  BOOST_CHECK_NO_THROW(scene::parse_scene(with("  dt: 0.01", "  dt: 0.01\n  dt_growth: 1"), "g.yaml"));
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  dt_growth: 0.9"), 5, "0.9", "analysis.dt_growth",
                  "out of range [1, inf]");
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  creep_tolerance: 1e-6\n  dt_growth: 2"), 6, "2",
                  "analysis.dt_growth", "fixed-step run only");
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  step_tolerance: 1e-4\n  dt_growth: 2"), 6, "2",
                  "analysis.dt_growth", "fixed-step run only");
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  dt_cut: 1"), 5, "1", "analysis.dt_cut", "out of range (0, 1)");
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  dt_cut: 0"), 5, "0", "analysis.dt_cut", "out of range (0, 1)");
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  solver_max_iterations: 0"), 5, "0",
                  "analysis.solver_max_iterations", "out of range [1, 1e+09]");
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  solver_max_iterations: 2.5"), 5, "2.5",
                  "analysis.solver_max_iterations", "not a whole number");
}

BOOST_AUTO_TEST_CASE(nan_and_inf_are_refused_anywhere) {
  expect_error_at(with("  dt: 0.01", "  dt: .nan"), 4, ".nan", "analysis.dt", "not a finite number");
  expect_error_at(with("[1.5, 1.5]", "[1.5, .inf]"), 15, ".inf", "measurement_points[0].point[1]", "not a finite number");
  expect_error_at(with("E2: 2", "E2: -.inf"), 10, "-.inf", "law.E2", "not a finite number");
  expect_error_at(with("[2, 2], [1, 2]]", "[2, .NaN], [1, 2]]"), 13, ".NaN", "blocks[1].polygon[2][1]", "not a finite number");
}

BOOST_AUTO_TEST_CASE(non_simple_and_degenerate_polygons_are_refused) {
  expect_error_at(with("[[1, 1], [2, 1], [2, 2], [1, 2]]", "[[1, 1], [2, 2], [2, 1], [1, 1.5]]"), 13, "[[1",
                  "blocks[1].polygon", "is not simple");
  expect_error_at(with("[[1, 1], [2, 1], [2, 2], [1, 2]], edge_joint_sets: [fault, bedding, bedding, bedding]",
                       "[[1, 1], [2, 1], [3, 1]], joint_set: fault"),
                  13, "[[1", "blocks[1].polygon", "degenerate");
  expect_error_at(with("[[1, 1], [2, 1], [2, 2], [1, 2]], edge_joint_sets: [fault, bedding, bedding, bedding]",
                       "[[1, 1], [2, 1], [2, 2], [1, 2], [1, 1]], joint_set: fault"),
                  13, "[[1", "blocks[1].polygon", "repeats its first vertex");
  expect_error_at(with("[[1, 1], [2, 1], [2, 2], [1, 2]], edge_joint_sets: [fault, bedding, bedding, bedding]",
                       "[[1, 1], [2, 1]], joint_set: fault"),
                  13, "[[1", "blocks[1].polygon", "at least 3");
}

BOOST_AUTO_TEST_CASE(overlapping_blocks_are_refused_touching_ones_accepted) {
  expect_error_at(with("[[1, 1], [2, 1], [2, 2], [1, 2]]", "[[1, 0.5], [2, 0.5], [2, 2], [1, 2]]"), 13, "{name: top",
                  "blocks[1]", "blocks 'base' and 'top' overlap");
  // The same block twice: every vertex on the other's boundary, interiors equal.
  expect_error_at(with("[[1, 1], [2, 1], [2, 2], [1, 2]]", "[[0, 0], [4, 0], [4, 1], [0, 1]]"), 13, "{name: top",
                  "blocks[1]", "overlap");
  BOOST_CHECK_NO_THROW(scene::parse_scene(kBaseScene, "touching.yaml"));  // top sits on base
}

BOOST_AUTO_TEST_CASE(edge_naming_an_unknown_joint_set_is_refused_with_a_hint) {
  expect_error_at(with("[fault, bedding, bedding, bedding]", "[fault, bedings, bedding, bedding]"), 13, "bedings",
                  "blocks[1].edge_joint_sets[1]", "unknown joint set 'bedings' (did you mean 'bedding'?)");
  expect_error_at(with("[fault, bedding, bedding, bedding]", "[fault, bedding, bedding]"), 13, "[fault",
                  "blocks[1].edge_joint_sets", "list of 4 joint set names");
  expect_error_at(with("joint_set: bedding,", "joint_set: rock,"), 12, "rock,", "blocks[0].joint_set",
                  "unknown joint set 'rock'");
}

BOOST_AUTO_TEST_CASE(duplicated_keys_and_names_are_refused) {
  expect_error_at(with("  dt: 0.01\n", "  dt: 0.01\n  dt: 0.02\n"), 5, "dt", "analysis.dt", "given twice (first at line 4)");
  expect_error_at(with("{name: top,", "{name: base,"), 13, "{name: base", "blocks[1].name", "'base' is used twice");
}

BOOST_AUTO_TEST_CASE(points_must_lie_on_a_block) {
  expect_error_at(with("[1.5, 1.5]", "[9, 9]"), 15, "[9", "measurement_points[0].point", "lies on no block");
  // On the joint between base and top: ambiguous unless `block:` says which.
  expect_error_at(with("[1.5, 1.5]}", "[1.5, 1]}"), 15, "[1.5", "measurement_points[0].point",
                  "boundary of several blocks (base, top)");
  const auto s = scene::parse_scene(with("[1.5, 1.5]}", "[1.5, 1], block: top}"), "ok.yaml");
  BOOST_TEST(s.measurement_points[0].at.block == 1);
  expect_error_at(with("[1.5, 1.5]}", "[3.5, 0.5], block: top}"), 15, "[3.5", "point", "not on block 'top'");
}

BOOST_AUTO_TEST_CASE(static_analysis_refuses_velocity_inputs) {
  expect_error_at(with("fixed: true}", "fixed: true, initial_velocity: [1, 0, 0]}"), 12, "[1, 0, 0]",
                  "blocks[0].initial_velocity", "static analysis carries no velocity");
  expect_error_at(with("  dt: 0.01\n", "  dt: 0.01\n  dynamic_ratio: 0.5\n"), 5, "0.5", "analysis.dynamic_ratio",
                  "needs `type: dynamic`");
}

BOOST_AUTO_TEST_CASE(damping_keys_need_a_dynamic_analysis_and_a_ratio_in_zero_one) {
  // Contact damping (joint set restitution) and block damping (material damping_ratio).
  expect_error_at(with("bedding: {friction_angle: 30}", "bedding: {friction_angle: 30, restitution: 0.5}"), 9, "0.5",
                  "joint_sets.bedding.restitution", "needs `analysis: {type: dynamic}`");
  expect_error_at(with("poisson_ratio: 0.25}", "poisson_ratio: 0.25, damping_ratio: 0.1}"), 7, "0.1",
                  "materials.rock.damping_ratio", "needs `analysis: {type: dynamic}`");
  const std::string dynamic = with("  duration: 1\n", "  type: dynamic\n  duration: 1\n");
  expect_error_at(with("bedding: {friction_angle: 30}", "bedding: {friction_angle: 30, restitution: 1.5}", dynamic), 10,
                  "1.5", "joint_sets.bedding.restitution", "");
  expect_error_at(with("poisson_ratio: 0.25}", "poisson_ratio: 0.25, damping_ratio: -0.1}", dynamic), 8, "-0.1",
                  "materials.rock.damping_ratio", "");
  const auto s = scene::parse_scene(
      with("poisson_ratio: 0.25}", "poisson_ratio: 0.25, damping_ratio: 0.2}",
           with("bedding: {friction_angle: 30}", "bedding: {friction_angle: 30, restitution: 0.3}", dynamic)),
      "damped.yaml");
  const scene::BuiltScene built = scene::build_scene(s);
  BOOST_TEST(built.model.materials[0].damping_ratio == 0.2);
  BOOST_TEST_REQUIRE(built.joint_sets[0].restitution.has_value());
  BOOST_TEST(*built.joint_sets[0].restitution == 0.3);
  BOOST_TEST(!built.joint_sets[1].restitution.has_value());
  // The 1 m x 1 m block (2600 kg/m) on the 40 x 1e9 Pa penalty: contact period
  // 2 pi sqrt(2600 / 4e10) = 1.6 ms; dt 0.01 s is above a tenth of it.
  auto warns = [](const scene::BuiltScene& b) {
    return std::any_of(b.warnings.begin(), b.warnings.end(), [](const std::string& w) {
      return w.find("joint set 'bedding': `restitution` acts as given only at dynamic steps below 0.00016 s") !=
             std::string::npos;
    });
  };
  BOOST_TEST(warns(built));
  const auto fine = scene::parse_scene(with("  dt: 0.01\n", "  dt: 0.0001\n",
                                            with("bedding: {friction_angle: 30}",
                                                 "bedding: {friction_angle: 30, restitution: 0.3}", dynamic)),
                                       "damped-fine.yaml");
  BOOST_TEST(!warns(scene::build_scene(fine)));
}

BOOST_AUTO_TEST_CASE(unresolved_restitution_is_one_short_warning_that_says_what_to_do_or_none_when_accepted) {
  // issue 52: every check and run of the Goodman example printed one such warning per
  // joint set, ~400 characters each, that its author could not act on (its stages
  // converge without resolving the contacts' vibration).
  const std::string dynamic = with("  duration: 1\n", "  type: dynamic\n  duration: 1\n");
  const std::string both = with("fault: {friction_angle: 20,", "fault: {friction_angle: 20, restitution: 0,",
                                with("bedding: {friction_angle: 30}", "bedding: {friction_angle: 30, restitution: 0}",
                                     dynamic));
  const auto about_restitution = [](const scene::BuiltScene& b) {
    std::vector<std::string> w;
    for (const auto& x : b.warnings)
      if (x.find("restitution") != std::string::npos) w.push_back(x);
    return w;
  };
  const auto w = about_restitution(scene::build_scene(scene::parse_scene(both, "both.yaml")));
  BOOST_TEST_REQUIRE(w.size() == 1u);  // one for both joint sets
  BOOST_TEST(w[0].find("joint sets 'bedding', 'fault':") == 0u, w[0]);
  BOOST_TEST(w[0].size() < 320u, w[0]);
  // What to do: a smaller dt (named with its value), or the key that accepts it.
  BOOST_TEST(w[0].find("and dt is 0.01 s: give a smaller dt or") != std::string::npos, w[0]);
  BOOST_TEST(w[0].find("`analysis.accept_unresolved_impacts: true`") != std::string::npos, w[0]);
  const auto accepted = scene::parse_scene(with("  dt: 0.01\n", "  dt: 0.01\n  accept_unresolved_impacts: true\n", both),
                                           "accepted.yaml");
  BOOST_TEST(accepted.analysis.accept_unresolved_impacts);
  BOOST_TEST(about_restitution(scene::build_scene(accepted)).empty());
  // The shipped examples that settle with restitution at unresolved steps accept it:
  // `check` and `run` print no warning for them.
  for (const char* example : {"examples/goodman-toppling.yaml", "examples/rockmass/jointed-slope.yaml",
                              "examples/rockmass/reservoir-slope.yaml", "examples/rockmass/tunnel.yaml",
                              "examples/rockmass/tunnel-stages.yaml"}) {
    const auto s = scene::load_scene(source_path(example));
    BOOST_TEST(scene::scene_warnings(s).empty(), example << ": " << (scene::scene_warnings(s).empty() ? "" : scene::scene_warnings(s)[0]));
    auto unaccepted = s;
    unaccepted.analysis.accept_unresolved_impacts = false;
    BOOST_TEST(about_restitution(scene::build_scene(unaccepted)).size() == 1u, example);
  }
}

BOOST_AUTO_TEST_CASE(loads_take_a_force_or_a_strictly_increasing_history) {
  const std::string loads = "loads:\n  - {point: [1.5, 2], history: [[0, 0, 0], [1, 5, -1], [1, 6, 0]]}\n";
  expect_error_at(kBaseScene + loads, 17, "[1, 6", "loads[0].history[2]", "times must increase strictly");
  const auto s = scene::parse_scene(kBaseScene + "loads:\n  - {point: [1.5, 2], force: [3, -4]}\n", "ok.yaml");
  BOOST_TEST(s.loads.size() == 1u);
  BOOST_TEST(s.loads[0].history.size() == 1u);
  BOOST_TEST(s.loads[0].history[0][2] == -4.0);
  expect_error_at(kBaseScene + "loads:\n  - {point: [1.5, 2]}\n", 17, "{point", "loads[0]", "exactly one of force");
}

BOOST_AUTO_TEST_CASE(yaml_syntax_errors_carry_line_and_column) {
  try {
    (void)scene::parse_scene(with("  dt: 0.01\n", "  dt: [0.01\n"), "syntax.yaml");
    BOOST_ERROR("no error");
  } catch (const scene::SceneError& e) {
    BOOST_TEST(e.line() > 0);
    BOOST_TEST(e.column() > 0);
    BOOST_TEST(e.message().find("YAML syntax") != std::string::npos);
  }
}

BOOST_AUTO_TEST_CASE(missing_file_is_a_scene_error_naming_it) {
  try {
    (void)scene::load_scene("/nonexistent/scene.yaml");
    BOOST_ERROR("no error");
  } catch (const scene::SceneError& e) {
    BOOST_TEST(e.file() == "/nonexistent/scene.yaml");
    BOOST_TEST(e.message().find("cannot open") != std::string::npos);
  }
}

BOOST_AUTO_TEST_SUITE_END()
