#include "run_totals.hpp"

#include <algorithm>
#include <cmath>

#include "rheodda/core/energy.hpp"

namespace rheodda::scene {

RunTotals::RunTotals(std::size_t joint_sets, bool static_analysis)
    : first_failure(joint_sets, std::numeric_limits<double>::quiet_NaN()) {
  mechanism.static_analysis = static_analysis;
}

void RunTotals::add(const core::StepReport& r, std::span<const contact::CreepCounters> counters) {
  cuts += r.cuts;
  redone += r.rejections;
  extrapolated += r.extrapolated ? 1 : 0;
  max_penetration = std::max(max_penetration, r.max_penetration);
  contact_changes += r.changes;
  auto& m = mechanism;
  if (r.collapse_stage) m.collapse_stages.push_back(r.time - r.dt);
  if (m.static_analysis && core::inertia_share(r.energy) > core::kMechanismStepShare) {
    if (m.steps++ == 0) {
      m.first_time = r.time;
      m.first_step = r.step;
    }
    m.last_time = r.time;
  }
  for (std::size_t j = 0; j < first_failure.size() && j < counters.size(); ++j)
    if (std::isnan(first_failure[j]) && counters[j].failures > 0) first_failure[j] = r.time;
}

}  // namespace rheodda::scene
