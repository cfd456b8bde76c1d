#include "rheodda/laws/builtin_laws.hpp"

#include <algorithm>
#include <cmath>

namespace rheodda::laws {

namespace {
using Kind = CreepElement::Kind;

// Units are per unit joint area (contact_rheology.hpp): with stress in MPa,
// length in mm and time in h, E is MPa/mm and eta is MPa*h/mm.
ParameterSpec stiffness(std::string name, std::string meaning) {
  return {std::move(name), "stress/length", std::move(meaning), 0.0, true};
}
ParameterSpec viscosity(std::string name, std::string meaning) {
  return {std::move(name), "stress*time/length", std::move(meaning), 0.0, true};
}
double at(const ParameterValues& p, const char* key) { return p.find(key)->second; }

template <class Law>
LawInfo make_info(std::string name, std::string summary, std::string equation,
                  std::vector<ParameterSpec> specs) {
  LawInfo info{std::move(name), std::move(summary), std::move(equation), std::move(specs), {}};
  info.make = [](const ParameterValues& p) -> std::unique_ptr<ContactRheology> {
    return std::make_unique<Law>(p);
  };
  return info;
}
}  // namespace

// ---- Maxwell ---------------------------------------------------------------
Maxwell::Maxwell(const ParameterValues& p)
    : SeriesLaw("maxwell", p, at(p, "E1"), {{Kind::dashpot, 0.0, at(p, "eta1"), 0.0}}) {}

std::optional<double> Maxwell::relaxation_modulus(double t) const {
  const double e1 = at(parameters(), "E1"), eta1 = at(parameters(), "eta1");
  return e1 * std::exp(-e1 * t / eta1);
}

LawInfo Maxwell::info() {
  return make_info<Maxwell>("maxwell", "spring E1 in series with dashpot eta1",
                            "d(t) = F/E1 + F*t/eta1",
                            {stiffness("E1", "instantaneous (elastic) shear stiffness"),
                             viscosity("eta1", "viscosity of the steady-creep dashpot")});
}

// ---- Kelvin ----------------------------------------------------------------
Kelvin::Kelvin(const ParameterValues& p)
    : SeriesLaw("kelvin", p, std::nullopt, {{Kind::kelvin, at(p, "E2"), at(p, "eta2"), 0.0}}) {}

LawInfo Kelvin::info() {
  return make_info<Kelvin>("kelvin", "spring E2 parallel to dashpot eta2 (Kelvin-Voigt)",
                           "d(t) = F/E2*(1 - exp(-E2*t/eta2))",
                           {stiffness("E2", "delayed-elastic (Kelvin) shear stiffness"),
                            viscosity("eta2", "viscosity of the Kelvin dashpot")});
}

// ---- Burgers ---------------------------------------------------------------
// The seed's eq. (2) with stress -> joint shear force per unit area (eq. 21).
Burgers::Burgers(const ParameterValues& p)
    : SeriesLaw("burgers", p, at(p, "E1"),
                {{Kind::kelvin, at(p, "E2"), at(p, "eta2"), 0.0},
                 {Kind::dashpot, 0.0, at(p, "eta1"), 0.0}}) {}

std::optional<double> Burgers::relaxation_modulus(double t) const {
  // Laplace: G(s) = (E1/eta2) (E2 + eta2 s) / ((s + r1)(s + r2)), with
  // r1 + r2 = E1/eta1 + E1/eta2 + E2/eta2 and r1 r2 = E1 E2/(eta1 eta2).
  // Partial fractions give G(t) = A e^-r1 t + B e^-r2 t, G(0) = E1.
  const auto& p = parameters();
  const double e1 = at(p, "E1"), e2 = at(p, "E2"), eta1 = at(p, "eta1"), eta2 = at(p, "eta2");
  const double sum = e1 / eta1 + e1 / eta2 + e2 / eta2;
  const double prod = (e1 / eta1) * (e2 / eta2);
  const double disc = std::sqrt(std::max(sum * sum - 4.0 * prod, 0.0));
  const double r1 = 0.5 * (sum + disc);  // fast root
  const double r2 = prod / r1;            // slow root, without cancellation
  const double a = (e1 / eta2) * (e2 - eta2 * r1) / (r2 - r1);
  const double b = (e1 / eta2) * (e2 - eta2 * r2) / (r1 - r2);
  return a * std::exp(-r1 * t) + b * std::exp(-r2 * t);
}

LawInfo Burgers::info() {
  return make_info<Burgers>(
      "burgers", "Maxwell (spring E1, dashpot eta1) in series with Kelvin (E2 || eta2)",
      "d(t) = F/E1 + F/E2*(1 - exp(-E2*t/eta2)) + F*t/eta1",
      {stiffness("E1", "instantaneous (elastic) shear stiffness"),
       stiffness("E2", "delayed-elastic (Kelvin) shear stiffness"),
       viscosity("eta1", "viscosity of the steady-creep (Maxwell) dashpot"),
       viscosity("eta2", "viscosity of the Kelvin dashpot")});
}

// ---- Nishihara -------------------------------------------------------------
Nishihara::Nishihara(const ParameterValues& p)
    : SeriesLaw("nishihara", p, at(p, "E1"),
                {{Kind::kelvin, at(p, "E2"), at(p, "eta2"), 0.0},
                 {Kind::bingham, 0.0, at(p, "eta3"), at(p, "Fs")}}) {}

std::optional<double> Nishihara::relaxation_modulus(double t) const {
  const auto& p = parameters();
  const double e1 = at(p, "E1"), e2 = at(p, "E2"), eta2 = at(p, "eta2");
  return e1 * e2 / (e1 + e2) + e1 * e1 / (e1 + e2) * std::exp(-(e1 + e2) * t / eta2);
}

LawInfo Nishihara::info() {
  ParameterSpec fs{"Fs", "stress", "viscoplastic threshold (yield) shear force per unit area", 0.0,
                   false};
  return make_info<Nishihara>(
      "nishihara",
      "spring E1 + Kelvin (E2 || eta2) + Bingham viscoplastic (eta3, threshold Fs) in series",
      "d(t) = F/E1 + F/E2*(1 - exp(-E2*t/eta2)) + <F - Fs>*t/eta3",
      {stiffness("E1", "instantaneous (elastic) shear stiffness"),
       stiffness("E2", "delayed-elastic (Kelvin) shear stiffness"),
       viscosity("eta2", "viscosity of the Kelvin dashpot"),
       viscosity("eta3", "viscosity of the viscoplastic (Bingham) dashpot"), fs});
}

// ---- Generalized Kelvin ------------------------------------------------------
GeneralizedKelvin::GeneralizedKelvin(const ParameterValues& p)
    : SeriesLaw("generalized-kelvin", p, at(p, "E1"),
                {{Kind::kelvin, at(p, "E2"), at(p, "eta2"), 0.0},
                 {Kind::kelvin, at(p, "E3"), at(p, "eta3"), 0.0}}) {}

std::optional<double> GeneralizedKelvin::relaxation_modulus(double t) const {
  // Laplace: the creep compliance is J(s) = (1/s) [1/E1 + 1/(E2 + eta2 s) + 1/(E3 + eta3 s)]
  // and G(s) = 1/(s^2 J(s)) = D(s)/(s N(s)) with D = E1 (E2 + eta2 s)(E3 + eta3 s) and
  // N = (E2 + eta2 s)(E3 + eta3 s) + E1 (E3 + eta3 s) + E1 (E2 + eta2 s) = A s^2 + B s + C.
  // Residues: D(0)/N(0) = G_inf at s = 0, D(-r)/(-r N'(-r)) at the roots s = -r.
  const auto& p = parameters();
  const double e1 = at(p, "E1"), e2 = at(p, "E2"), eta2 = at(p, "eta2"), e3 = at(p, "E3"),
               eta3 = at(p, "eta3");
  const double qa = eta2 * eta3;
  const double qb = e2 * eta3 + e3 * eta2 + e1 * eta3 + e1 * eta2;
  const double qc = e2 * e3 + e1 * e3 + e1 * e2;
  const double disc = std::sqrt(std::max(qb * qb - 4.0 * qa * qc, 0.0));
  const double r1 = (qb + disc) / (2.0 * qa);  // fast root
  const double r2 = qc / (qa * r1);            // slow root, without cancellation
  auto d_at = [&](double s) { return e1 * (e2 + eta2 * s) * (e3 + eta3 * s); };
  const double g_inf = e1 * e2 * e3 / qc;
  // N'(-r1) = B - 2 A r1 = -disc, N'(-r2) = B - 2 A r2 = +disc.
  const double a1 = d_at(-r1) / (r1 * disc);
  const double a2 = -d_at(-r2) / (r2 * disc);
  return g_inf + a1 * std::exp(-r1 * t) + a2 * std::exp(-r2 * t);
}

LawInfo GeneralizedKelvin::info() {
  return make_info<GeneralizedKelvin>(
      "generalized-kelvin", "spring E1 + Kelvin (E2 || eta2) + Kelvin (E3 || eta3) in series",
      "d(t) = F/E1 + F/E2*(1 - exp(-E2*t/eta2)) + F/E3*(1 - exp(-E3*t/eta3))",
      {stiffness("E1", "instantaneous (elastic) shear stiffness"),
       stiffness("E2", "stiffness of the first Kelvin spring"),
       viscosity("eta2", "viscosity of the first Kelvin dashpot"),
       stiffness("E3", "stiffness of the second Kelvin spring"),
       viscosity("eta3", "viscosity of the second Kelvin dashpot")});
}

}  // namespace rheodda::laws
