// The creep error estimate of adaptive creep stepping (creep_error.hpp;
// docs/reference/step-controls.md, "Adaptive creep stepping") and the retraction
// of a step whose estimate is too large. The step-start records are those the
// commit replaced (kept by end_step when begin_step was asked for the
// estimate), so neither the estimate nor a retraction copies the contact system.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <unordered_map>
#include <utility>

#include "law_call_site.hpp"
#include "rheodda/contact/contact_system.hpp"
#include "rheodda/contact/creep_error.hpp"

namespace rheodda::contact {

void CreepErrorEstimate::estimate(std::span<const Contact> start_contacts,
                                  std::span<const laws::RheologyState> start_rheology,
                                  std::span<const Contact> end, std::span<const JointSet> joint_sets,
                                  std::span<const step::LawStep> law_steps, double dt) {
  changes_ = 0;
  retract_prev_tau_ = prev_tau_;
  retract_prev_dt_ = prev_dt_;
  std::unordered_map<std::uint64_t, std::size_t> start_of;
  start_of.reserve(start_contacts.size());
  for (std::size_t k = 0; k < start_contacts.size(); ++k) start_of[start_contacts[k].id] = k;
  // State changes of creeping contacts on joint sets with a law: a
  // contact that locks, slides or opens moves load onto its neighbours at once.
  auto creeps = [&](const Contact& c) {
    return c.tributary_length > 0.0 && c.joint_set >= 0 &&
           c.joint_set < static_cast<int>(joint_sets.size()) && joint_sets[c.joint_set].law != nullptr;
  };
  std::size_t matched_locked = 0;
  for (const Contact& c : end) {
    const auto it = start_of.find(c.id);
    if (it == start_of.end()) {
      if (creeps(c) && c.state != ContactState::open) ++changes_;
      continue;
    }
    const Contact& s = start_contacts[it->second];
    if (s.state == ContactState::locked && creeps(s)) ++matched_locked;
    if ((creeps(c) || creeps(s)) && s.state != c.state) ++changes_;
  }
  std::size_t start_locked = 0;
  for (const Contact& s : start_contacts)
    if (s.state == ContactState::locked && creeps(s)) ++start_locked;
  changes_ += static_cast<int>(start_locked - matched_locked);  // vanished while locked
  // Per joint set: the scheme the step used and the constants to compare with.
  struct Pair {
    laws::Scheme used;
    laws::StepConstants main, other;  // the used scheme's and exponential-linear's (or implicit's)
  };
  std::vector<std::optional<Pair>> ks(joint_sets.size());
  std::unordered_map<std::uint64_t, double> tau_now;
  tau_now.reserve(end.size());
  double worst = 0.0;
  for (const Contact& c : end) {
    if (c.rheology < 0 || c.tributary_length <= 0.0 || c.state != ContactState::locked ||
        c.creep_failed)  // a failed damage law no longer creeps (docs/reference/rheology-in-dda.md, "Failure")
      continue;
    const auto it = start_of.find(c.id);
    if (it == start_of.end()) continue;
    const Contact& s = start_contacts[it->second];
    if (s.rheology < 0 || s.tributary_length <= 0.0 || s.state != ContactState::locked) continue;
    const auto& law = joint_sets[c.joint_set].law;
    if (!law) continue;
    auto& k = ks[c.joint_set];
    if (!k) {
      // The scheme the step used (ContactSystem::scheme_used).
      const laws::Scheme used = c.joint_set < static_cast<int>(law_steps.size()) && law_steps[c.joint_set].active
                                    ? law_steps[c.joint_set].scheme
                                    : laws::Scheme::implicit;
      const laws::Scheme other = used == laws::Scheme::exponential_linear
                                     ? laws::Scheme::implicit
                                     : laws::Scheme::exponential_linear;
      k = Pair{used, law->step_constants(dt, used), law->step_constants(dt, other)};
    }
    // Stresses tau = F / l at the step's start and end (docs/reference/rheology-in-dda.md, Units).
    const double tau_s = s.shear_force / s.tributary_length, tau_e = c.shear_force / c.tributary_length;
    tau_now[c.id] = tau_s;
    const laws::RheologyState& old = start_rheology[s.rheology];
    laws::RheologyState next;
    double err = 0.0;
    const laws::CallSiteScope at(law_call_site(c));
    if (k->used != laws::Scheme::exponential_linear) {
      // First-order scheme: its increment minus the exponential-linear one (the
      // exact increment for a force linear over the step) is its local error.
      err = std::abs(law->advance(k->main, old, tau_s, tau_e, next) -
                     law->advance(k->other, old, tau_s, tau_e, next));
    } else {
      // Exponential-linear is exact for a force linear over the step; its local
      // error is the creep of the force's departure from linear:
      // |tau''| dt^2 / 12 times the step compliance c (Delta d = h + c tau_e,
      // laws/contact_rheology.hpp eq. 1), c ~ dt/eta for dt << eta/E (the
      // trapezoid-rule remainder). tau'' from the stresses at the start of the
      // last step, at the start and at the end of this one.
      const auto p = prev_tau_.find(c.id);
      if (p == prev_tau_.end() || prev_dt_ <= 0.0) continue;
      const double h1 = prev_dt_, h2 = dt;
      const double curvature =
          2.0 * ((tau_e - tau_s) / h2 - (tau_s - p->second) / h1) / (h1 + h2);
      const laws::Linearization lin = law->linearize(k->other, old, tau_s, tau_e);
      err = std::abs(curvature) * h2 * h2 / 12.0 * lin.c;
    }
    // A damage law that fails within the step under one scheme and not the
    // other has an infinite difference; NaN (both infinite) is as bad.
    if (std::isnan(err)) err = std::numeric_limits<double>::infinity();
    worst = std::max(worst, err);
  }
  prev_tau_.swap(tau_now);
  prev_dt_ = dt;
  error_ = worst;
}

void CreepErrorEstimate::retract() {
  prev_tau_ = retract_prev_tau_;
  prev_dt_ = retract_prev_dt_;
  skip();
}

std::vector<std::pair<std::uint64_t, double>> CreepErrorEstimate::previous_stress() const {
  // Sorted, so that equal states give equal files (the map's order is not defined).
  std::vector<std::pair<std::uint64_t, double>> s(prev_tau_.begin(), prev_tau_.end());
  std::sort(s.begin(), s.end());
  return s;
}

void CreepErrorEstimate::restore(std::span<const std::pair<std::uint64_t, double>> previous_stress,
                                 double previous_dt, double error, int state_changes) {
  prev_tau_.clear();
  prev_tau_.insert(previous_stress.begin(), previous_stress.end());
  prev_dt_ = previous_dt;
  error_ = error;
  changes_ = state_changes;
}

bool ContactSystem::retract_step() {
  if (!start_.retractable) return false;
  records_.committed.swap(start_.records);
  energy_.committed.swap(start_.work);
  records_.counters = start_.counters;
  last_max_penetration_ = start_.last_max_penetration;
  penalty_ = start_.penalty;
  energy_.stored_before = start_.stored_before;
  creep_error_.retract();
  abandon_step();  // no trial records: the step-start states remain
  start_.retractable = false;
  return true;
}

}  // namespace rheodda::contact
