#include "rheodda/laws/contact_rheology.hpp"

#include <limits>
#include <string>

#include "rheodda/laws/parameters.hpp"

namespace rheodda::laws {

std::string_view scheme_name(Scheme s) {
  switch (s) {
    case Scheme::lagged: return "lagged";
    case Scheme::implicit: return "implicit";
    case Scheme::exponential_linear: return "exponential-linear";
  }
  return "?";
}

Scheme parse_scheme(std::string_view name) {
  if (name == "lagged") return Scheme::lagged;
  if (name == "implicit") return Scheme::implicit;
  if (name == "exponential-linear") return Scheme::exponential_linear;
  throw LawError("scheme", "unknown integration scheme '" + std::string(name) +
                               "'; use one of: lagged, implicit, exponential-linear");
}

double ContactRheology::displacement_closed_form(double force, double t) const {
  const auto e1 = instantaneous_stiffness();
  return (e1 ? force / *e1 : 0.0) + creep_closed_form(force, t);
}

double ClosedFormCapability::creep_closed_form(double, double) const {
  return std::numeric_limits<double>::quiet_NaN();
}

std::optional<double> ClosedFormCapability::relaxation_modulus(double) const { return std::nullopt; }

double ForceDependenceCapability::linear_limit() const { return std::numeric_limits<double>::infinity(); }

std::optional<double> FailureCapability::failure_time(double) const { return std::nullopt; }

double FailureCapability::time_to_failure(const RheologyState&, double) const {
  return std::numeric_limits<double>::infinity();
}

std::optional<double> FailureCapability::failure_in_step(const StepConstants&, const RheologyState&,
                                                         double, double) const {
  return std::nullopt;
}

}  // namespace rheodda::laws
