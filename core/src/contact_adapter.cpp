#include "rheodda/core/contact_adapter.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <unordered_map>
#include <utility>

namespace rheodda::core {

contact::ContactSettings contact_settings_for(const Model& model, double penalty_factor) {
  double e_max = 0.0;
  for (const Material& m : model.materials) e_max = std::max(e_max, m.young_modulus);
  contact::ContactSettings s;
  s.penalty = penalty_factor * e_max;
  // Dynamic analysis, or a dynamic settling stage (ContactSettings::lock_at_touch;
  // the steps say which are dynamic: StepContext::dynamic).
  s.lock_at_touch = model.settings.has_dynamic_steps();
  s.reversal_at_normal_resolution = s.lock_at_touch;     // (ContactSettings::reversal_at_normal_resolution)
  return s;
}

void ContactAdapter::begin_step(std::span<const contact::BlockView> blocks, const StepContext& ctx) {
  system_.begin_step(blocks, ctx.max_displacement, ctx.dt, ctx.dynamic, ctx.inertia);
  dt_ = ctx.dt;
  want_error_ = ctx.creep_error_wanted;
}

void ContactAdapter::assemble(std::span<const contact::BlockView> blocks,
                              contact::SystemSink& sink) {
  system_.assemble(blocks, sink);
}

ContactCheck ContactAdapter::check(std::span<const contact::BlockView> blocks,
                                   const Eigen::VectorXd& D) {
  const contact::CheckResult r = system_.check(blocks, D);
  return {r.state_changes, r.max_penetration,
          ContactChanges{r.closed, r.opened, r.slipped, r.stuck, r.refinements}};
}

void ContactAdapter::end_step(std::span<const contact::BlockView> blocks, const Eigen::VectorXd& D) {
  can_retract_ = false;
  creep_changes_ = 0;
  if (!want_error_) {
    system_.end_step(blocks, D);
    creep_error_ = 0.0;
    return;
  }
  // Keep the whole system as it is before the commit, so that the host can
  // retract the step (copy-assignment reuses the buffers of the last copy).
  if (saved_)
    *saved_ = system_;
  else
    saved_.emplace(system_);
  saved_prev_tau_ = prev_tau_;
  saved_prev_dt_ = prev_dt_;
  can_retract_ = true;
  const std::span<const contact::Contact> start_contacts = saved_->contacts();
  const std::span<const laws::RheologyState> start_rheology = saved_->rheology_states();
  system_.end_step(blocks, D);
  std::unordered_map<std::uint64_t, std::size_t> start_of;
  start_of.reserve(start_contacts.size());
  for (std::size_t k = 0; k < start_contacts.size(); ++k) start_of[start_contacts[k].id] = k;
  // State changes of creeping contacts on joint sets with a law: a
  // contact that locks, slides or opens moves load onto its neighbours at once.
  const auto& law_sets = system_.joint_sets();
  auto creeps = [&](const contact::Contact& c) {
    return c.tributary_length > 0.0 && c.joint_set >= 0 &&
           c.joint_set < static_cast<int>(law_sets.size()) && law_sets[c.joint_set].law != nullptr;
  };
  std::size_t matched_locked = 0;
  for (const contact::Contact& c : system_.contacts()) {
    const auto it = start_of.find(c.id);
    if (it == start_of.end()) {
      if (creeps(c) && c.state != contact::ContactState::open) ++creep_changes_;
      continue;
    }
    const contact::Contact& s = start_contacts[it->second];
    if (s.state == contact::ContactState::locked && creeps(s)) ++matched_locked;
    if ((creeps(c) || creeps(s)) && s.state != c.state) ++creep_changes_;
  }
  std::size_t start_locked = 0;
  for (const contact::Contact& s : start_contacts)
    if (s.state == contact::ContactState::locked && creeps(s)) ++start_locked;
  creep_changes_ += static_cast<int>(start_locked - matched_locked);  // vanished while locked
  // Per joint set: the scheme the step used and the constants to compare with.
  const auto& sets = system_.joint_sets();
  struct Pair {
    laws::Scheme used;
    laws::StepConstants main, other;  // the used scheme's and exponential-linear's (or implicit's)
  };
  std::vector<std::optional<Pair>> ks(sets.size());
  std::unordered_map<std::uint64_t, double> tau_now;
  tau_now.reserve(system_.contacts().size());
  double worst = 0.0;
  for (const contact::Contact& c : system_.contacts()) {
    if (c.rheology < 0 || c.tributary_length <= 0.0 || c.state != contact::ContactState::locked ||
        c.creep_failed)  // a failed damage law no longer creeps (docs/rheology-in-dda.md, "Failure")
      continue;
    const auto it = start_of.find(c.id);
    if (it == start_of.end()) continue;
    const contact::Contact& s = start_contacts[it->second];
    if (s.rheology < 0 || s.tributary_length <= 0.0 || s.state != contact::ContactState::locked) continue;
    const auto& law = sets[c.joint_set].law;
    if (!law) continue;
    auto& k = ks[c.joint_set];
    if (!k) {
      const laws::Scheme used = system_.scheme_used(c.joint_set).value_or(laws::Scheme::implicit);
      const laws::Scheme other = used == laws::Scheme::exponential_linear
                                     ? laws::Scheme::implicit
                                     : laws::Scheme::exponential_linear;
      k = Pair{used, law->step_constants(dt_, used), law->step_constants(dt_, other)};
    }
    // Stresses tau = F / l at the step's start and end (docs/rheology-in-dda.md, Units).
    const double tau_s = s.shear_force / s.tributary_length, tau_e = c.shear_force / c.tributary_length;
    tau_now[c.id] = tau_s;
    const laws::RheologyState& old = start_rheology[s.rheology];
    laws::RheologyState next;
    double err = 0.0;
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
      const double h1 = prev_dt_, h2 = dt_;
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
  prev_dt_ = dt_;
  creep_error_ = worst;
}

void ContactAdapter::abandon_step() { system_.abandon_step(); }

namespace {
struct SystemSnapshot final : ContactSnapshot {
  explicit SystemSnapshot(const contact::ContactSystem& s) : system(s) {}
  contact::ContactSystem system;
};
}  // namespace

std::unique_ptr<ContactSnapshot> ContactAdapter::snapshot() const {
  return std::make_unique<SystemSnapshot>(system_);
}

void ContactAdapter::restore(const ContactSnapshot& s) {
  system_ = dynamic_cast<const SystemSnapshot&>(s).system;
}

bool ContactAdapter::extrapolate(const ContactSnapshot& coarse) {
  return system_.extrapolate(dynamic_cast<const SystemSnapshot&>(coarse).system);
}

bool ContactAdapter::retract_step() {
  if (!can_retract_) return false;
  system_ = *saved_;
  system_.abandon_step();  // drop the copied trial records: the step-start states remain
  prev_tau_ = saved_prev_tau_;
  prev_dt_ = saved_prev_dt_;
  can_retract_ = false;
  creep_error_ = 0.0;
  creep_changes_ = 0;
  return true;
}

}  // namespace rheodda::core
