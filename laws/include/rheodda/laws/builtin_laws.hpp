// The built-in laws: Maxwell, Kelvin (Kelvin-Voigt), Burgers, Nishihara and the
// generalized Kelvin law. Each is a SeriesLaw configuration plus its closed
// forms; see docs/reference/laws.md.
#pragma once

#include "rheodda/laws/registry.hpp"
#include "rheodda/laws/series_law.hpp"

namespace rheodda::laws {

/// Maxwell: spring E1 in series with dashpot eta1. d(t) = F/E1 + F t/eta1.
class Maxwell final : public SeriesLaw {
 public:
  explicit Maxwell(const ParameterValues& p);
  /// G(t) = E1 exp(-E1 t/eta1).
  std::optional<double> relaxation_modulus(double t) const override;
  static LawInfo info();
};

/// Kelvin-Voigt: spring E2 parallel to dashpot eta2. d(t) = F/E2 (1 - exp(-E2 t/eta2)).
/// No instantaneous spring, hence no relaxation under a held displacement step.
class Kelvin final : public SeriesLaw {
 public:
  explicit Kelvin(const ParameterValues& p);
  static LawInfo info();
};

/// Burgers (the seed's eq. 2): Maxwell (E1, eta1) in series with Kelvin (E2, eta2).
/// d(t) = F/E1 + F/E2 (1 - exp(-E2 t/eta2)) + F t/eta1.
class Burgers final : public SeriesLaw {
 public:
  explicit Burgers(const ParameterValues& p);
  /// G(t) = A exp(-r1 t) + B exp(-r2 t), roots of eta1 eta2 s^2 + (eta1 E2 + E1 eta1 + E1 eta2) s + E1 E2.
  std::optional<double> relaxation_modulus(double t) const override;
  static LawInfo info();
};

/// Nishihara: spring E1 + Kelvin (E2, eta2) + Bingham viscoplastic (eta3, threshold Fs).
/// d(t) = F/E1 + F/E2 (1 - exp(-E2 t/eta2)) + <F - Fs> t/eta3.
class Nishihara final : public SeriesLaw {
 public:
  explicit Nishihara(const ParameterValues& p);
  /// Standard linear solid below the threshold: E1 E2/(E1+E2) + E1^2/(E1+E2) exp(-(E1+E2) t/eta2).
  std::optional<double> relaxation_modulus(double t) const override;
  static LawInfo info();
};

/// Generalized Kelvin: spring E1 + Kelvin (E2, eta2) + Kelvin (E3, eta3) in series.
/// d(t) = F/E1 + F/E2 (1 - exp(-E2 t/eta2)) + F/E3 (1 - exp(-E3 t/eta3)).
/// Two retardation times, no steady creep (docs/design/law-interface.md, "Adding a law").
class GeneralizedKelvin final : public SeriesLaw {
 public:
  explicit GeneralizedKelvin(const ParameterValues& p);
  /// G(t) = G_inf + A1 exp(-r1 t) + A2 exp(-r2 t), G_inf = 1/(1/E1 + 1/E2 + 1/E3),
  /// -r1, -r2 the roots of eta2 eta3 s^2 + (E2 eta3 + E3 eta2 + E1 eta3 + E1 eta2) s
  /// + E2 E3 + E1 E3 + E1 E2.
  std::optional<double> relaxation_modulus(double t) const override;
  static LawInfo info();
};

}  // namespace rheodda::laws
