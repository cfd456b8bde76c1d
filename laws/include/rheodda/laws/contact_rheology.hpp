// The contact rheology interface: what the DDA host needs from a creep law.
//
// Why this shape. A DDA step is solved several times (the open-close iteration),
// so a law never owns history: it is an immutable parameter object with pure
// functions of (old state, forces) -> (new state). The host keeps one plain
// RheologyState per contact that has a law, and a copy of the old one for rollback.
//
// Units. Laws are written per unit area of joint: "force" F below is a shear
// stress (e.g. MPa), "displacement" is a shear displacement (e.g. mm), a
// stiffness E is stress/length (MPa/mm) and a viscosity eta is
// stress*time/length (MPa*h/mm). Any consistent set works; the contact layer
// converts contact forces to stresses by dividing by the contact area.
//
// The creep increment over a step is affine in the end-of-step force F_e:
//     Delta d_c = h + c * F_e                                   (1)
// (docs/reference/laws.md; ../shared/reference/rheology.md "three schemes"). For the
// lagged scheme c = 0 and h is the seed's increment, eq. (12)/(22). For the
// implicit scheme c is the step's creep compliance, which the host folds into
// the shear spring: k_eff = k / (1 + k c), and h is the history term that goes
// to the load vector. Laws with a threshold (Nishihara) are piecewise affine:
// linearize() returns the piece that holds at a guessed F_e.
//
// Nonlinear laws (power-law creep, damage; Linearity::nonlinear). The increment
// Delta d_c(F_e) is a smooth nonlinear function of F_e, and linearize() returns
// its tangent at the guess F_g:
//     c = dDelta d_c/dF_e (F_g),   h = Delta d_c(F_g) - c F_g          (1')
// so that (1) is the Newton model of the increment. The host re-linearizes at
// every open-close iterate and stops when the model's error at the iterate is
// below its tolerance (docs/reference/rheology-in-dda.md, "Nonlinear laws: Newton in the
// open-close iteration"); an affine law's (1) is exact, so the host never
// re-linearizes it and affine laws cost what they did.
#pragma once

#include <array>
#include <optional>
#include <string_view>

#include "rheodda/laws/parameters.hpp"

namespace rheodda::laws {

/// How the force that drives a step's creep is chosen (docs/reference/laws.md, "Schemes").
enum class Scheme {
  lagged,             ///< F = force at the start of the step (the seed's eqs. 12-16); explicit,
                      ///< 1st order; with a series spring k stable only for dt < 2 eta/k
  implicit,           ///< F = force at the end of the step; unconditionally stable and
                      ///< monotone, 1st order (the choice for stiff DDA contact springs)
  exponential_linear  ///< F linear over the step, exact exponential integral; 2nd order,
                      ///< exact for ramps; stable, but rings (decaying) under a stiff
                      ///< series spring when dt > 2 eta/k
};

/// Name used on the command line, in YAML and in CSV: "lagged", "implicit", "exponential-linear".
std::string_view scheme_name(Scheme s);
/// Parses a scheme name; throws LawError naming the allowed values.
Scheme parse_scheme(std::string_view name);

/// Most internal displacements a law may keep (one per creep element in series).
inline constexpr int kMaxInternal = 4;

/// History of one contact: the displacement of each creep element [length].
/// The total creep displacement d_c is the sum of the used slots.
struct RheologyState {
  std::array<double, kMaxInternal> q{};
  /// Damage D of a damage-coupled law (docs/reference/laws.md, "damage-burgers") [-]:
  /// 0 intact, 1 failed; always 0 for laws without damage.
  double damage = 0.0;
  double creep() const { return q[0] + q[1] + q[2] + q[3]; }
  /// True once the law reached failure (damage 1): the contact's creep strength is gone.
  bool failed() const { return damage >= 1.0; }
};

/// How the creep increment of a step depends on the end-of-step force F_e.
enum class Linearity {
  affine,            ///< (1) holds exactly for every F_e (Maxwell, Kelvin, Burgers, ...)
  piecewise_affine,  ///< (1) holds on pieces; linearize() picks the piece of the guess (Nishihara)
  nonlinear          ///< smooth in F_e; linearize() returns the tangent (1') (power-law laws)
};

/// Per-element constants for one step size, computed once per law and step
/// (the exponential is evaluated here, never per contact).
///
/// The element's increment over the step is written as
///     Delta q = per_q q + per_start g(F_s) + per_end g(F_e)            (2)
/// with g(F) = F for a Kelvin element or a dashpot and g(F) = sign(F)<|F| - Fs>
/// for a Bingham element (docs/reference/laws.md, "Schemes"), so that advance() costs a
/// few multiply-adds per element whatever the element or the scheme.
struct UnitStepConstants {
  double b = 0.0;    ///< 1 - exp(-dt E/eta) for a Kelvin element [-]
  double phi = 0.0;  ///< 1 - b/r, r = dt E/eta: weight of the force ramp [-]
  double dt_over_eta = 0.0;  ///< dt/eta for a dashpot or Bingham element [length/force]
  double per_q = 0.0;      ///< coefficient of the old q in (2) [-]
  double per_start = 0.0;  ///< coefficient of g(F_s) in (2) [length/force]
  double per_end = 0.0;    ///< coefficient of g(F_e) in (2) [length/force]
  double threshold = 0.0;  ///< Bingham threshold Fs [force]; 0 for linear elements
  bool bingham = false;    ///< true: g is the Bingham excess; false: g(F) = F
};

/// Everything a law needs to know about a step that does not depend on the contact.
struct StepConstants {
  double dt = 0.0;  ///< step size [time]
  Scheme scheme = Scheme::implicit;
  int count = 0;    ///< number of elements (used entries of `unit`)
  std::array<UnitStepConstants, kMaxInternal> unit{};
};

/// The affine form (1) of the creep increment over a step.
struct Linearization {
  double h = 0.0;  ///< history part of Delta d_c [length]
  double c = 0.0;  ///< creep compliance of the step [length/force]
};

// ---- What a law must give, and what it may ------------------------------------
//
// The essence, ContactRheology's pure virtual functions, is what every law gives
// and all a running analysis needs to creep a contact: its name and parameters,
// how many state slots it keeps, and the creep increment of a step with the state
// after it (step_constants, linearize, advance). What only some laws have, or
// only some callers ask, is in the small capability interfaces below, whose
// defaults are the answers of a law that lacks it; a law overrides those it has.
// ContactRheology takes them all, so the host and the tools call one object and a
// new law writes nothing for a capability it does not have
// (docs/design/law-interface.md, "What a law must give, and what it may").

/// Capability: an elastic spring in series with the creep elements.
class SeriesSpringCapability {
 public:
  virtual ~SeriesSpringCapability() = default;
  /// The instantaneous series spring E1 [force/length], if the law has one
  /// (Maxwell, Burgers, Nishihara): a contact's shear spring is then E1 times its
  /// tributary length. Default: none (Kelvin), the joint set's shear stiffness is
  /// the spring.
  virtual std::optional<double> instantaneous_stiffness() const { return std::nullopt; }
};

/// Capability: how creep depends on the force. The defaults claim nothing: a law
/// that does not say it is linear is linearized again at every open-close iterate,
/// which is right for any law (an affine law that says so is solved in one).
class ForceDependenceCapability {
 public:
  virtual ~ForceDependenceCapability() = default;
  /// True when creep is linear in force (Boltzmann superposition holds). Default: false.
  virtual bool is_linear() const { return false; }
  /// How the step's creep increment depends on F_e; by default affine for a
  /// linear law and piecewise affine otherwise (the built-in SeriesLaw laws).
  virtual Linearity linearity() const {
    return is_linear() ? Linearity::affine : Linearity::piecewise_affine;
  }
  /// Force below which the law is linear [force]. Default: infinity (as for linear laws).
  virtual double linear_limit() const;
};

/// Capability: closed-form responses, for the verification, `rheodda law curve`'s
/// exact column and exact_displacement / exact_force (history.hpp); a running
/// analysis never asks for them.
class ClosedFormCapability {
 public:
  virtual ~ClosedFormCapability() = default;
  /// Closed-form creep displacement (without the instantaneous spring) at time t
  /// [time] under a constant force F applied at t = 0 [length]. Default: NaN, the
  /// law has none (the closed-form displacements derived from it are NaN too).
  virtual double creep_closed_form(double force, double t) const;
  /// Relaxation modulus G(t) [force/length]: force per unit displacement held
  /// from t = 0, where the law has a closed form (nullopt otherwise, the default).
  /// For a law with a threshold it holds only while |force| stays below it.
  virtual std::optional<double> relaxation_modulus(double t) const;
};

/// Capability: failure of a damage-coupled law (RheologyState::damage reaching 1;
/// docs/reference/rheology-in-dda.md, "Failure"). The defaults are those of a law
/// that never fails.
class FailureCapability {
 public:
  virtual ~FailureCapability() = default;
  /// Failure time [time] under a constant force applied at t = 0 to an intact
  /// law (closed form): when its damage reaches 1. nullopt for laws that never
  /// fail or at a force that does not damage.
  virtual std::optional<double> failure_time(double force) const;
  /// Time [time] left before failure from state `s` if the force stays at
  /// `force` (infinity for laws without damage or at zero damage rate).
  virtual double time_to_failure(const RheologyState& s, double force) const;
  /// Time from the start of a step [time] at which the law fails within it,
  /// under the scheme's force (the force linear from force_start to force_end
  /// over the step where the scheme uses both); nullopt if it does not fail
  /// within the step (always for laws without damage).
  virtual std::optional<double> failure_in_step(const StepConstants& k, const RheologyState& old,
                                                double force_start, double force_end) const;
};

/// A contact rheology law: the essence (pure virtual, below) and the optional
/// capabilities above. Implementations are immutable after construction.
class ContactRheology : public SeriesSpringCapability,
                        public ForceDependenceCapability,
                        public ClosedFormCapability,
                        public FailureCapability {
 public:
  ~ContactRheology() override = default;

  /// Registry name, e.g. "burgers".
  virtual std::string_view name() const = 0;
  /// The validated parameter values the law was built from (registry names).
  virtual const ParameterValues& parameters() const = 0;
  /// Number of RheologyState slots the law uses (1..kMaxInternal).
  virtual int internal_count() const = 0;

  /// Constants of a step of size dt [time] for a scheme.
  virtual StepConstants step_constants(double dt, Scheme scheme) const = 0;
  /// Affine form (1) of the creep increment over the step, given the old state,
  /// the force at the start of the step and a guess of the force at its end
  /// (the guess selects the piece of a piecewise-affine law, and is the point of
  /// the tangent (1') of a nonlinear law).
  virtual Linearization linearize(const StepConstants& k, const RheologyState& old,
                                  double force_start, double force_end_guess) const = 0;
  /// Advances the state over the step; returns Delta d_c [length].
  /// Repeatable: `old` is never modified, so a step can be redone from it.
  virtual double advance(const StepConstants& k, const RheologyState& old, double force_start,
                         double force_end, RheologyState& next) const = 0;

  /// Closed-form total displacement under constant force: F/E1 + creep [length]
  /// (from the series spring and closed-form capabilities).
  double displacement_closed_form(double force, double t) const;
};

}  // namespace rheodda::laws
