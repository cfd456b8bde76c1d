// A law built from creep elements in series with an optional instantaneous
// spring: the shape of all five built-in laws (Burgers = spring + Kelvin +
// dashpot, and so on). Each element's step math lives here once; a law is a
// configuration of elements (docs/design/law-interface.md, "Adding a law").
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "rheodda/laws/contact_rheology.hpp"

namespace rheodda::laws {

/// One creep element in series.
struct CreepElement {
  enum class Kind {
    kelvin,   ///< spring E parallel to dashpot eta: eta q' + E q = F
    dashpot,  ///< viscous dashpot: eta q' = F
    bingham   ///< viscoplastic: eta q' = sign(F) <|F| - threshold>
  };
  Kind kind = Kind::dashpot;
  double E = 0.0;          ///< Kelvin spring [force/length]
  double eta = 0.0;        ///< viscosity [force*time/length]
  double threshold = 0.0;  ///< Bingham yield force [force]
};

/// Contact rheology as an optional spring E1 in series with creep elements.
class SeriesLaw : public ContactRheology {
 public:
  SeriesLaw(std::string name, ParameterValues parameters, std::optional<double> spring,
            std::vector<CreepElement> elements);

  std::string_view name() const override { return name_; }
  const ParameterValues& parameters() const override { return parameters_; }
  int internal_count() const override { return static_cast<int>(elements_.size()); }
  std::optional<double> instantaneous_stiffness() const override { return spring_; }
  bool is_linear() const override;

  StepConstants step_constants(double dt, Scheme scheme) const override;
  Linearization linearize(const StepConstants& k, const RheologyState& old, double force_start,
                          double force_end_guess) const override;
  double advance(const StepConstants& k, const RheologyState& old, double force_start,
                 double force_end, RheologyState& next) const override;
  double creep_closed_form(double force, double t) const override;
  double linear_limit() const override;

  const std::vector<CreepElement>& elements() const { return elements_; }

  /// Largest step [time] at which the lagged scheme stays stable when the law acts
  /// in series with a shear spring of stiffness k (same unit as E): the smallest of
  /// its elements' limits (docs/notes/step-controls.md, "Stability"): a Kelvin element
  /// (E, eta) is stable at any step when k <= E, otherwise for
  ///   dt < -(eta/E) ln(1 - 2E/(k + E));
  /// a dashpot or a Bingham element above its threshold for dt < 2 eta/k.
  /// Infinity when no element limits the step.
  double lagged_step_limit(double k) const;

 private:
  std::string name_;
  ParameterValues parameters_;
  std::optional<double> spring_;
  std::vector<CreepElement> elements_;
};

/// Numerically careful helpers of the Kelvin step, exposed for tests.
/// b(r) = 1 - exp(-r) (via expm1); phi(r) = 1 - b(r)/r (series for small r).
double kelvin_b(double r);
double kelvin_phi(double r);

}  // namespace rheodda::laws
