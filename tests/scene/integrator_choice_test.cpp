// `integrator: automatic` (scene/include/rheodda/scene/integrator_choice.hpp;
// docs/reference/explicit-step.md, "Automatic choice"): a small scene takes the implicit step, a
// large running-bond wall the explicit one, by the estimated CPU per dynamic step; a scene the
// explicit step cannot take takes the implicit one, saying why; the choice reaches the engine.
#include <boost/test/unit_test.hpp>

#include <fmt/format.h>

#include <string>

#include "test_support.hpp"
#include "rheodda/scene/build.hpp"
#include "rheodda/scene/integrator_choice.hpp"

using namespace rheodda;
using namespace rheodda::test;

namespace {

/// A dynamic scene of a running-bond wall of nx x ny bricks 0.2 m x 0.1 m on a fixed base
/// (the wall of docs/notes/explicit-step.md: E = 5 GPa, nu = 0.25, 2.6 t/m^3, friction 30 deg,
/// dt = 1 ms), under `integrator: automatic`.
std::string wall_scene(int nx, int ny) {
  const double w = 0.2, h = 0.1, width = nx * w;  // m
  std::string text = fmt::format(
      "units: {{length: m, force: N, time: s}}\n"
      "analysis: {{type: dynamic, duration: 0.01, dt: 0.001, gravity: [0, -9.81], integrator: automatic}}\n"
      "materials:\n"
      "  rock: {{density: 2600, young_modulus: 5.0e9, poisson_ratio: 0.25}}\n"
      "joint_sets:\n"
      "  joint: {{friction_angle: 30}}\n"
      "blocks:\n"
      "  - {{name: base, rectangle: {{x: -0.5, y: -0.5, width: {:.17g}, height: 0.5}}, joint_set: joint, fixed: true}}\n",
      width + 1.0);
  auto brick = [&](int row, int k, double x0, double x1) {
    text += fmt::format("  - {{name: b{}_{}, rectangle: {{x: {:.17g}, y: {:.17g}, width: {:.17g}, height: {:.17g}}}, "
                        "joint_set: joint}}\n",
                        row, k, x0, row * h, x1 - x0, h);
  };
  for (int j = 0; j < ny; ++j) {
    if (j % 2 == 0) {
      for (int i = 0; i < nx; ++i) brick(j, i, i * w, (i + 1) * w);
    } else {
      brick(j, 0, 0.0, 0.5 * w);
      for (int i = 0; i + 1 < nx; ++i) brick(j, i + 1, (i + 0.5) * w, (i + 1.5) * w);
      brick(j, nx, width - 0.5 * w, width);
    }
  }
  return text;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(integrator_choice)

BOOST_AUTO_TEST_CASE(a_small_wall_takes_the_implicit_step_and_a_large_one_the_explicit_step) {
  // The estimate's fit (integrator_choice.cpp) puts the wall's crossing at about 1 000 blocks:
  // 10 x 10 bricks (about 100) implicit, 50 x 50 (about 2 500) explicit.
  const scene::SceneDescription small = scene::parse_scene(wall_scene(10, 10), "small.yaml");
  const scene::IntegratorChoice a = scene::choose_integrator(small);
  BOOST_TEST_MESSAGE("10 x 10: " << a.reason);
  BOOST_TEST((a.integrator == core::Integrator::implicit));
  BOOST_TEST(a.reason.find("automatic: implicit, estimated CPU per dynamic step") != std::string::npos);
  BOOST_TEST(a.implicit_seconds > 0.0);
  BOOST_TEST(a.explicit_seconds > a.implicit_seconds);
  BOOST_TEST((scene::build_scene(small).model.settings.integrator == core::Integrator::implicit));

  const scene::SceneDescription large = scene::parse_scene(wall_scene(50, 50), "large.yaml");
  const scene::IntegratorChoice b = scene::choose_integrator(large);
  BOOST_TEST_MESSAGE("50 x 50: " << b.reason);
  BOOST_TEST((b.integrator == core::Integrator::explicit_step));
  BOOST_TEST(b.reason.find("automatic: explicit, estimated CPU per dynamic step") != std::string::npos);
  BOOST_TEST(b.explicit_seconds > 0.0);
  BOOST_TEST(b.explicit_seconds < b.implicit_seconds);
  BOOST_TEST((scene::build_scene(large).model.settings.integrator == core::Integrator::explicit_step));
}

BOOST_AUTO_TEST_CASE(a_scene_the_explicit_step_cannot_take_takes_the_implicit_one_and_says_why) {
  // The base scene is static without a dynamic settling stage: no dynamic step.
  const auto s = scene::parse_scene(with("  dt: 0.01", "  dt: 0.01\n  integrator: automatic"), "static.yaml");
  const scene::IntegratorChoice c = scene::choose_integrator(s);
  BOOST_TEST((c.integrator == core::Integrator::implicit));
  BOOST_TEST(c.reason == "automatic: implicit, since a static analysis without a dynamic settling stage has no "
                         "dynamic step");
  BOOST_TEST(c.explicit_seconds == 0.0);
  // A dynamic analysis that carries no velocity: the engine refuses the explicit step.
  const auto still = scene::parse_scene(
      with("  dt: 0.01", "  dt: 0.01\n  type: dynamic\n  dynamic_ratio: 0\n  integrator: automatic"), "still.yaml");
  const scene::IntegratorChoice d = scene::choose_integrator(still);
  BOOST_TEST_MESSAGE("dynamic_ratio 0: " << d.reason);
  BOOST_TEST((d.integrator == core::Integrator::implicit));
  BOOST_TEST(d.reason.find("automatic: implicit, since the explicit step refuses the scene") == 0u);
  BOOST_TEST((scene::build_scene(still).model.settings.integrator == core::Integrator::implicit));
  // The words given are kept; the explicit step's keys are taken under `automatic`.
  BOOST_TEST(scene::choose_integrator(scene::parse_scene(kBaseScene, "base.yaml")).reason == "given");
  const auto keys = with("  dt: 0.01", "  dt: 0.01\n  type: dynamic\n  integrator: automatic\n  explicit_safety: 0.5");
  BOOST_TEST(scene::parse_scene(keys, "keys.yaml").analysis.explicit_safety == 0.5);
}

BOOST_AUTO_TEST_SUITE_END()
