// Stability map of the creep schemes (docs/speed-accuracy.md, "Stability map").
//
// Model: a shear spring k in series with a Kelvin element (E2, eta2) - the
// seed's Kelvin part of the Burgers joint, Table 1 row 1 (E2 = 192.43 MPa/mm,
// eta2 = 2141.23 MPa h/mm) - held at a displacement delta from t = 0 (stress
// relaxation). Solved with the law alone: laws::solve_series_force gives the end
// force of each step from the spring and the law's affine creep increment
// (the same algebra as the DDA contact's k_eff = k / (1 + k c), eq. 2 of
// docs/rheology-in-dda.md), then ContactRheology::advance.
// Growth: largest |F| over steps 100-200 divided by the force at t = 0+ (k delta):
// at most 1 for a stable run (the exact force decays monotonically to
// k E2 / (k + E2) delta); > 1 means the step amplifies the force (unstable).
// The lagged scheme (exact exponential under the start force, the seed's
// eqs. 12-16) amplifies an error by 1 - b (k + E2)/E2, b = 1 - exp(-dt E2/eta2):
// stable for dt E2/eta2 < -ln(1 - 2/(k/E2 + 1)) when k > E2, at any dt when
// k <= E2; for k >> E2 this is dt < 2 eta2 / (k + E2) (docs/rheology-in-dda.md).
//
// Usage: stability_map [--csv FILE]   (prints a Markdown table; FILE gets
//        scheme,dt_E2_over_eta2,k_over_E2,growth for scripts/accuracy-report.sh)
#include <cmath>
#include <cstdio>
#include <string>

#include "rheodda/laws/history.hpp"
#include "rheodda/laws/registry.hpp"

using namespace rheodda;

namespace {

constexpr double kE2 = 192.43, kEta2 = 2141.23;  // [MPa/mm], [MPa h/mm] (Table 1 row 1)

/// Growth factor of a relaxation run of `steps` steps (see the header).
double growth(laws::Scheme scheme, double x, double y, int steps = 200) {
  const auto law = laws::LawRegistry::builtin().create("kelvin", {{"E2", kE2}, {"eta2", kEta2}});
  const double dt = x * kEta2 / kE2, k = y * kE2, delta = 1e-3;  // [h], [MPa/mm], [mm]
  const laws::StepConstants ks = law->step_constants(dt, scheme);
  laws::RheologyState q, next;
  double force = k * delta, worst = 0.0;  // the spring's response at t = 0+
  for (int n = 1; n <= steps; ++n) {
    const double f = laws::solve_series_force(*law, ks, q, k, delta, force);
    law->advance(ks, q, force, f, next);
    q = next;
    force = f;
    if (!std::isfinite(f)) return INFINITY;
    if (n > steps / 2) worst = std::max(worst, std::abs(f));
  }
  return worst / (k * delta);
}

}  // namespace

int main(int argc, char** argv) {
  FILE* csv = nullptr;
  if (argc == 3 && std::string(argv[1]) == "--csv") {
    csv = std::fopen(argv[2], "w");
    if (!csv) {
      std::fprintf(stderr, "stability_map: cannot write %s\n", argv[2]);
      return 2;
    }
    std::fprintf(csv, "scheme,dt_E2_over_eta2,k_over_E2,growth\n");
  } else if (argc != 1) {
    std::fprintf(stderr, "usage: stability_map [--csv FILE]\n");
    return 2;
  }
  const laws::Scheme schemes[] = {laws::Scheme::lagged, laws::Scheme::implicit,
                                  laws::Scheme::exponential_linear};
  // Map: dt E2/eta2 and k/E2 from 1e-2 to 1e3, 4 points per decade.
  int stable[3] = {0, 0, 0}, total = 0, lagged_as_predicted = 0;
  double worst_stable[3] = {0, 0, 0};
  for (int i = 0; i <= 20; ++i)
    for (int j = 0; j <= 20; ++j) {
      const double x = std::pow(10.0, -2.0 + 0.25 * i), y = std::pow(10.0, -2.0 + 0.25 * j);
      ++total;
      for (int s = 0; s < 3; ++s) {
        const double g = growth(schemes[s], x, y);
        if (csv)
          std::fprintf(csv, "%s,%.6g,%.6g,%.6g\n", std::string(laws::scheme_name(schemes[s])).c_str(),
                       x, y, std::isfinite(g) ? g : 1e300);
        const bool ok = g <= 1.0 + 1e-12;
        stable[s] += ok;
        if (ok) worst_stable[s] = std::max(worst_stable[s], g);
        if (s == 0 && ok == (y <= 1.0 || x < -std::log(1.0 - 2.0 / (y + 1.0)))) ++lagged_as_predicted;
      }
    }
  std::printf("Map: dt E2/eta2 and k/E2 each from 1e-2 to 1e3 (21 x 21 = %d points), "
              "200 steps of relaxation per point.\n\n",
              total);
  std::printf("| scheme | stable points | largest growth among them |\n|---|---:|---:|\n");
  for (int s = 0; s < 3; ++s)
    std::printf("| %s | %d / %d | %.4f |\n", std::string(laws::scheme_name(schemes[s])).c_str(),
                stable[s], total, worst_stable[s]);
  std::printf("\nLagged: stable exactly where predicted (k <= E2, or dt E2/eta2 < -ln(1 - 2 E2/(k + E2))) "
              "at %d of %d points.\n",
              lagged_as_predicted, total);
  if (csv) std::fclose(csv);
  return 0;
}
