// The seed's two-block shear creep test (Section 4, Figure 6) run by the DDA
// engine with the Burgers joints of Table 1: prints, per row and scheme, the
// largest deviation of the joint's shear displacement from the closed form
// (the seed's eqs. 20-21) and the time per step; with --csv DIR also writes
// DIR/row<i>.csv (t [h], DDA d [mm], closed-form d [mm]) and
// DIR/closed<i>.csv (the closed form every 0.5 h) for scripts/plot-shear-creep.sh. Units MPa, mm, h, unit thickness.
// Usage: shear_creep_table1 [--csv DIR]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include "rheodda/contact/contact_system.hpp"
#include "rheodda/core/contact_adapter.hpp"
#include "rheodda/core/engine.hpp"
#include "rheodda/laws/registry.hpp"
#include "rheodda/laws/seed_table1.hpp"
#include "two_block.hpp"  // tests/models

using namespace rheodda;

namespace {

using Row = laws::SeedTable1Row;
constexpr const auto& kTable1 = laws::kSeedTable1;

/// Block A (100 x 100 mm) on block B (fixed), F1 and F2 on A at the joint line.
core::Model scene(const Row& r, double dt) {
  const double w = 100.0;
  core::Model m = models::two_block_model(w, dt);
  m.point_loads.push_back({1, {0.5 * w, 0.0}, {{0.0, {0.0, -r.sigma * w}}}});
  m.point_loads.push_back({1, {0.5 * w, 0.0}, {{0.0, {r.tau * w, 0.0}}}});
  return m;
}

using models::joint_shear;  // along F2, mean over A's base contacts [mm]

}  // namespace

int main(int argc, char** argv) {
  std::optional<std::string> csv_dir;
  if (argc == 3 && std::string(argv[1]) == "--csv") csv_dir = argv[2];
  const double dt = 2.0, t_end = 200.0;  // [h]
  std::printf("two-block shear creep, Table 1 Burgers joints, dt = %g h, 0-%g h\n", dt, t_end);
  std::printf("%-6s %-30s %14s %16s %12s\n", "tau", "scheme", "d(200 h) [mm]", "max rel. error",
              "us/step");
  const std::optional<laws::Scheme> schemes[] = {laws::Scheme::lagged, laws::Scheme::implicit,
                                                 laws::Scheme::exponential_linear, std::nullopt};
  for (size_t i = 0; i < std::size(kTable1); ++i) {
    const Row& r = kTable1[i];
    std::shared_ptr<const laws::ContactRheology> law = laws::LawRegistry::builtin().create(
        "burgers", {{"E1", r.E1}, {"E2", r.E2}, {"eta1", r.eta1}, {"eta2", r.eta2}});
    for (const auto& scheme : schemes) {
      const core::Model m = scene(r, dt);
      models::SeedJointRun run(m, law, scheme);  // tests/models/two_block.hpp
      auto& [contacts, adapter, engine] = run;
      FILE* out = nullptr;
      if (csv_dir && !scheme) {
        out = std::fopen((*csv_dir + "/row" + std::to_string(i) + ".csv").c_str(), "w");
        if (!out) return 1;
        std::fprintf(out, "t,dda,closed_form\n");
        // The closed form from t = 0+ (the instantaneous response tau/E1) on a fine grid.
        FILE* exact = std::fopen((*csv_dir + "/closed" + std::to_string(i) + ".csv").c_str(), "w");
        if (!exact) return 1;
        std::fprintf(exact, "t,closed_form\n");
        for (int k = 0; k <= 400; ++k)
          std::fprintf(exact, "%g,%.10g\n", 0.5 * k,
                       law->displacement_closed_form(r.tau, k == 0 ? 1e-12 : 0.5 * k));
        std::fclose(exact);
      }
      double worst = 0.0;
      const auto t0 = std::chrono::steady_clock::now();
      while (engine.time() < t_end - 1e-9) {
        engine.step();
        const double d = joint_shear(contacts);
        const double e = law->displacement_closed_form(r.tau, engine.time());
        worst = std::max(worst, std::abs(d - e) / e);
        if (out) std::fprintf(out, "%g,%.10g,%.10g\n", engine.time(), d, e);
      }
      const double us = std::chrono::duration<double, std::micro>(
                            std::chrono::steady_clock::now() - t0).count() / engine.step_count();
      if (out) std::fclose(out);
      const std::string name =
          scheme ? std::string(laws::scheme_name(*scheme))
                 : "default (" + std::string(laws::scheme_name(*contacts.scheme_used(0))) + ")";
      std::printf("%-6.3f %-30s %14.7f %16.3e %12.1f\n", r.tau, name.c_str(), joint_shear(contacts),
                  worst, us);
    }
  }
  return 0;
}
