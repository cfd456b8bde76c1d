// The Goodman & Bray toppling slope (tests/contact/engine/goodman_bray.hpp) measured
// (docs/notes/explicit-step.md, "Toppling"): prints, never asserts.
//
//   toppling_probe le [PHI]      the limit-equilibrium angle phi_LE and, at PHI (default
//                                phi_LE), the block-by-block forces of the analysis
//   toppling_probe dda [options] the largest block displacement [m] of the DDA model of
//                                tests/contact/engine/toppling_test.cpp (goodman_bray_dda.hpp)
//                                at each of --times, for each friction angle phi_LE + --dphi
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "goodman_bray_dda.hpp"

using namespace rheodda;
using namespace rheodda::testing;

int main(int argc, char** argv) {
  CLI::App app{"Goodman-Bray toppling slope: limit equilibrium and DDA"};
  app.require_subcommand(1);
  const goodman_bray::Slope s;
  const double phi_le = goodman_bray::critical_friction_angle(s);

  auto* le = app.add_subcommand("le", "limit-equilibrium analysis");
  double phi = phi_le;
  le->add_option("phi", phi, "friction angle [deg]");

  auto* dda = app.add_subcommand("dda", "DDA runs");
  std::vector<double> dphis{0.0}, times{3.0};
  std::string integrator = "implicit", solver = "open-close";
  goodman_bray::DdaOptions o;
  dda->add_option("--dphi", dphis, "friction angles phi - phi_LE [deg]")->expected(1, -1);
  dda->add_option("--times", times, "times [s], ascending")->expected(1, -1);
  dda->add_option("--integrator", integrator)->check(CLI::IsMember({"implicit", "explicit"}));
  dda->add_option("--solver", solver)->check(CLI::IsMember({"open-close", "newton"}));
  dda->add_option("--dt", o.dt, "step [s]");
  dda->add_option("--young", o.young_modulus, "Young's modulus of the blocks [Pa]");
  dda->add_option("--penalty", o.penalty_factor, "contact penalty / E");
  dda->add_option("--safety", o.explicit_safety, "explicit_safety");
  dda->add_option("--damping", o.explicit_damping, "explicit_damping");
  dda->add_flag("--stick-keeps-force", o.stick_keeps_force, "joints' stick_keeps_force (default: Shi's rule)");
  CLI11_PARSE(app, argc, argv);

  if (le->parsed()) {
    std::printf("phi_LE = %.4f deg\nat phi = %.4f deg: P_0 = %.4f m^2\n", phi_le, phi, goodman_bray::toe_force(s, phi));
    std::printf("| n | y_n | M_n | L_n | P_{n-1,t} | P_{n-1,s} | mode |\n|---:|---:|---:|---:|---:|---:|---|\n");
    for (const auto& r : goodman_bray::analysis(s, phi)) {
      const char* mode = r.mode == goodman_bray::Mode::topples ? "topples"
                         : r.mode == goodman_bray::Mode::slides ? "slides" : "stable";
      std::printf("| %d | %.1f | %.1f | %.1f | ", r.n, r.y, r.M, r.L);
      if (r.L > 0.0) std::printf("%.1f", r.p_topple); else std::printf("-");
      std::printf(" | %.1f | %s |\n", r.p_slide, mode);
    }
    return 0;
  }
  o.integrator = integrator == "explicit" ? core::Integrator::explicit_step : core::Integrator::implicit;
  o.solver = solver == "newton" ? core::ContactSolver::newton : core::ContactSolver::open_close;
  std::printf("phi_LE = %.4f deg; %s (%s), dt %g s, E %g Pa, penalty %g E", phi_le, integrator.c_str(), solver.c_str(),
              o.dt, o.young_modulus, o.penalty_factor);
  if (o.integrator == core::Integrator::explicit_step) {
    const core::Settings defaults;
    std::printf(", explicit_safety %g, explicit_damping %g",
                o.explicit_safety > 0.0 ? o.explicit_safety : defaults.explicit_safety,
                o.explicit_damping >= 0.0 ? o.explicit_damping : defaults.explicit_damping);
  } else {
    std::printf(", %s", o.stick_keeps_force ? "stick_keeps_force" : "Shi's stick rule");
  }
  std::printf("\n");
  for (const double d : dphis) {
    o.phi_deg = phi_le + d;
    const auto t0 = std::chrono::steady_clock::now();
    const auto u = goodman_bray::largest_displacements(s, o, times);
    const double cpu = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("phi_LE %+.2f deg (%.3f):", d, o.phi_deg);
    for (std::size_t k = 0; k < times.size(); ++k) std::printf("  %g s: %.4g m", times[k], u[k]);
    std::printf("  (%.1f s)\n", cpu);
    std::fflush(stdout);
  }
  return 0;
}
