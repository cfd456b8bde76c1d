// Cost of creep laws on the contacts: a running-bond brick wall (NX x NY
// bricks 0.2 m x 0.1 m on a fixed base, gravity, static analysis, dt = 60 s)
// with every joint lawless (same elastic shear stiffness), then with the Burgers law of the seed's Table 1
// row 1 under each scheme. Prints the time per step, the contact assembly
// time, the contacts and rheology slots, and the largest joint creep after
// the run. Asserts nothing.
// Usage: shear_creep_wall [--steps S]   (default 20 steps; walls of 10x10 and 32x32 bricks)
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "rheodda/contact/contact_system.hpp"
#include "rheodda/core/contact_adapter.hpp"
#include "rheodda/core/engine.hpp"
#include "rheodda/laws/registry.hpp"
#include "brick_wall.hpp"  // tests/models

using namespace rheodda;
using core::Vec2;
using Clock = std::chrono::steady_clock;

namespace {

/// The benchmark wall (tests/models/brick_wall.hpp, nu = 0.2) as a static analysis of 60 s steps.
core::Model brick_wall(int nx, int ny) {
  core::Model m = models::running_bond_wall(nx, ny);
  m.settings.dt = 60.0;            // [s]
  m.settings.dynamic_ratio = 0.0;  // static analysis
  return m;
}

}  // namespace

int main(int argc, char** argv) {
  int steps = 20;
  for (int k = 1; k < argc; ++k) {
    if (!std::strcmp(argv[k], "--steps") && k + 1 < argc) steps = std::atoi(argv[++k]);
    else {
      std::fprintf(stderr, "usage: shear_creep_wall [--steps S]\n");
      return 2;
    }
  }
  // Table 1 row 1 in SI: E [Pa/m] = 1e9 x E [MPa/mm]; eta [Pa s/m] = 3.6e12 x eta [MPa h/mm].
  std::shared_ptr<const laws::ContactRheology> burgers = laws::LawRegistry::builtin().create(
      "burgers", {{"E1", 26.87e9}, {"E2", 192.43e9}, {"eta1", 34807.72 * 3.6e12},
                  {"eta2", 2141.23 * 3.6e12}});
  std::printf("# running-bond brick wall, static, dt = 60 s, %d steps (one core)\n", steps);
  std::printf("%7s %-30s %8s %6s %10s %10s %7s %14s\n", "blocks", "joints", "contacts", "slots",
              "step_ms", "assemb_ms", "iters", "max_creep_m");
  struct Variant {
    const char* name;
    bool law;
    std::optional<laws::Scheme> scheme;
  };
  // "no law" keeps the law's elastic shear stiffness (shear_stiffness = E1),
  // so the variants differ only by the creep work.
  const Variant variants[] = {{"no law (shear_stiffness = E1)", false, std::nullopt},
                              {"burgers, lagged", true, laws::Scheme::lagged},
                              {"burgers, implicit", true, laws::Scheme::implicit},
                              {"burgers, exponential-linear", true, laws::Scheme::exponential_linear},
                              {"burgers, default", true, std::nullopt}};
  for (int side : {10, 32}) {
    for (const Variant& v : variants) {
      core::Model model = brick_wall(side, side);
      contact::JointSet joint;
      joint.name = "mortar";
      joint.friction_angle = 30.0;
      if (v.law) joint.law = burgers;
      else joint.shear_stiffness = 26.87e9;  // [Pa/m]
      contact::ContactSettings s = core::contact_settings_for(model);
      s.scheme = v.scheme;
      contact::ContactSystem contacts({joint}, s);
      core::ContactAdapter adapter(contacts);
      core::Engine engine(model, adapter);
      const auto t0 = Clock::now();
      engine.run(steps);
      const double step_ms =
          1e3 * std::chrono::duration<double>(Clock::now() - t0).count() / steps;
      double assembly = 0.0, iters = 0.0;
      for (const auto& r : engine.reports()) assembly += r.assembly_seconds, iters += r.iterations;
      double max_creep = 0.0;
      for (const auto& st : contacts.rheology_states()) max_creep = std::max(max_creep, std::abs(st.creep()));
      std::printf("%7d %-30s %8zu %6zu %10.2f %10.2f %7.2f %14.3e\n", engine.block_count() - 1,
                  v.name, contacts.contacts().size(), contacts.rheology_states().size(), step_ms,
                  1e3 * assembly / steps, iters / steps, max_creep);
      std::fflush(stdout);
    }
  }
  return 0;
}
