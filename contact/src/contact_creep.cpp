// The creep laws on the contacts (docs/reference/rheology-in-dda.md): per joint set and
// step the law's constants and scheme, per locked contact the affine form of
// its creep increment (the seam in its shear spring), failures of damage laws.
#include "rheodda/laws/automatic_scheme.hpp"
#include "rheodda/contact/contact_system.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "contact_geometry.hpp"
#include "rheodda/contact/strength.hpp"
#include "law_call_site.hpp"

#include "rheodda/laws/series_law.hpp"

namespace rheodda::contact {

std::optional<laws::Scheme> ContactSystem::scheme_used(int js) const {
  if (js < 0 || js >= static_cast<int>(step_.laws.size()) || !step_.laws[js].active)
    return std::nullopt;
  return step_.laws[js].scheme;
}

const laws::StepConstants& ContactSystem::step_constants_of(size_t c) const {
  const LawStep& ls = step_.laws[records_.work.contacts[c].joint_set];
  return step_.hot[c].creep_from_rest ? ls.from_rest : ls.main;
}

void ContactSystem::linearize(size_t c, double tau_guess) {
  // Delta d_c = h + c tau_e (laws/contact_rheology.hpp) with tau = F / l_t:
  // locking point shifted by h, compliance c / l_t in force terms.
  const Contact& r = records_.work.contacts[c];
  const laws::CallSiteScope at(law_call_site(r));
  const laws::Linearization lin = joint_sets_[r.joint_set].law->linearize(
      step_constants_of(c), records_.work.rheology[r.rheology], step_.hot[c].tau_start, tau_guess);
  step_.seams[c] = {-lin.h, lin.c / r.tributary_length};
}

double ContactSystem::time_to_failure() const {
  double t = std::numeric_limits<double>::infinity();
  for (const Contact& r : records_.committed.contacts)
    if (r.state == ContactState::locked && r.rheology >= 0 && r.tributary_length > 0.0 &&
        !r.creep_failed && joint_sets_[r.joint_set].law)
      t = std::min(t, joint_sets_[r.joint_set].law->time_to_failure(
                          records_.committed.rheology[r.rheology], r.shear_force / r.tributary_length));
  return t;
}

void ContactSystem::fail_law(size_t c, double creep) {
  // docs/reference/rheology-in-dda.md, "Failure": a residual frictional joint from now on.
  // The creep up to the failure is the step's last: a fixed shift of the locking
  // point (compliance 0), as the law's own curve ends its creep at the failure
  // (laws/accurate_curve.cpp). Where the law's creep diverges at failure
  // (damage-burgers with n >= r + 1) none is kept.
  Contact& r = records_.work.contacts[c];
  Hot& h = step_.hot[c];
  h.law_failed = true;
  h.failure_creep = std::isfinite(creep) ? creep : 0.0;
  r.creep_failed = true;
  if (r.rheology >= 0) records_.work.rheology[r.rheology] = {};  // no history left
  r.intact = false;
  const JointSet& js = joint_sets_[r.joint_set];  // its residual strength from now on
  h.tan_phi = tan_deg(js.friction_angle_of(false));
  h.cohesion = js.cohesion_of(false);
  h.tensile_strength = 0.0;
  step_.seams[c] = {-h.failure_creep, 0.0};
}

void ContactSystem::start_laws(double dt) {
  // Law constants, once per joint set and step (never per contact). The
  // automatic scheme looks at the stiffest spring per unit area of the set.
  step_.laws.assign(joint_sets_.size(), LawStep{});
  const bool any_law = std::any_of(joint_sets_.begin(), joint_sets_.end(),
                                   [](const JointSet& j) { return j.law != nullptr; });
  if (dt > 0.0 && any_law) {
    const std::vector<Contact>& work = records_.work.contacts;
    std::vector<double> k_area(joint_sets_.size(), 0.0);
    for (size_t c = 0; c < work.size(); ++c)
      if (work[c].rheology >= 0 && work[c].tributary_length > 0.0)
        k_area[work[c].joint_set] = std::max(k_area[work[c].joint_set], step_.hot[c].ps / work[c].tributary_length);
    for (size_t j = 0; j < joint_sets_.size(); ++j) {
      const auto& law = joint_sets_[j].law;
      if (!law) continue;
      LawStep& ls = step_.laws[j];
      ls.active = true;
      ls.scheme = settings_.scheme ? *settings_.scheme : laws::automatic_scheme(*law, k_area[j], dt);
      ls.main = law->step_constants(dt, ls.scheme);
      ls.from_rest = law->step_constants(dt, laws::Scheme::implicit);
    }
    for (size_t c = 0; c < work.size(); ++c)
      if (work[c].rheology >= 0 && work[c].tributary_length > 0.0 && !work[c].creep_failed)
        linearize(c, step_.hot[c].tau_start);
  }
}

}  // namespace rheodda::contact
