// The warnings of what a fitted law carries into a scene (law_choice.hpp): the
// parameters its data do not determine, the duration and the stresses it was tested
// at, against the run. docs/guide/fitting.md, "What a fitted law carries into a scene".
#include "law_choice.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <span>

#include "rheodda/laws/registry.hpp"
#include "rheodda/scene/keys.hpp"

namespace rheodda::scene::detail {

namespace {

const laws::ParameterSpec& spec_of(const LawChoice& law, const std::string& name) {
  const auto& specs = laws::LawRegistry::builtin().get(law.name).parameters;
  return *std::find_if(specs.begin(), specs.end(), [&](const auto& p) { return p.name == name; });
}

std::string g3(double v) { return fmt::format("{:.3g}", v); }

/// "7.1 times below": how far `v` lies from `ref`, `v` < `ref`.
std::string times(double big, double small) {
  return small > 0.0 ? fmt::format("{:.2g} times", big / small) : std::string("infinitely many times");
}

}  // namespace

std::vector<std::string> law_choice_warnings(const SceneDescription& s) {
  std::vector<std::string> out;
  const std::string& tu = s.units.time;
  for (const auto& js : s.joint_sets) {
    if (!js.law) continue;
    const LawChoice& law = *js.law;
    if (!law.unidentified.empty()) {
      std::string values, decides;
      for (const auto& name : law.unidentified) {
        const auto& p = spec_of(law, name);
        values += fmt::format("{}{} = {:g} {}", values.empty() ? "" : ", ", name, law.parameters.at(name),
                              unit_text(p.unit, s.units));
        decides += "; " + p.what_its_value_decides() +
                   (p.unit == "stress" ? " (run compares the contacts' shear stresses with it)" : "");
      }
      out.push_back(fmt::format(
          "joint set '{}': the data law {} was fitted to do not determine {} (unidentified): {} {} one value among "
          "many the data allow{}. Prefer a law the data support (rheodda fit --law all gives the verdict) or a test "
          "that determines {} (docs/guide/fitting.md, \"What a fitted law carries into a scene\")",
          js.name, law.name, fmt::join(law.unidentified, ", "), values, law.unidentified.size() == 1 ? "is" : "are each",
          decides, law.unidentified.size() == 1 ? "it" : "them"));
    }
    if (law.tested_duration && s.analysis.duration > *law.tested_duration)
      out.push_back(fmt::format(
          "joint set '{}': the run lasts {:g} {}, {} the longest test law {} was fitted to (tested_duration {:g} {}): "
          "beyond it the law's creep is an extrapolation of the data",
          js.name, s.analysis.duration, tu, times(s.analysis.duration, *law.tested_duration) + " as long as", law.name,
          *law.tested_duration, tu));
  }
  return out;
}

bool law_stresses_checked(const SceneDescription& s) {
  for (const auto& js : s.joint_sets) {
    if (!js.law) continue;
    if (js.law->tested_stress) return true;
    for (const auto& name : js.law->unidentified)
      if (spec_of(*js.law, name).unit == "stress") return true;
  }
  return false;
}

std::vector<std::string> law_stress_warnings(const SceneDescription& s, std::span<const contact::Contact> contacts,
                                             double time, const std::string& when) {
  std::vector<std::string> out;
  const std::string su = s.units.stress();
  for (std::size_t j = 0; j < s.joint_sets.size(); ++j) {
    const auto& js = s.joint_sets[j];
    if (!js.law) continue;
    const LawChoice& law = *js.law;
    // The shear stress of each locked contact of the set with a law [stress].
    std::vector<double> tau;
    for (const auto& c : contacts)
      if (c.joint_set == static_cast<int>(j) && c.state == contact::ContactState::locked && c.rheology >= 0 &&
          c.tributary_length > 0.0)
        tau.push_back(std::abs(c.shear_force) / c.tributary_length);
    if (tau.empty()) continue;
    std::sort(tau.begin(), tau.end());
    const std::size_t n = tau.size();
    const double median = n % 2 ? tau[n / 2] : 0.5 * (tau[n / 2 - 1] + tau[n / 2]);
    const double lowest = tau.front(), highest = tau.back();
    auto share = [&](std::size_t k) {
      return fmt::format("{} of its {} locked contacts ({:.0f} %)", k, n, 100.0 * double(k) / double(n));
    };
    const std::string stresses = fmt::format("(median {} {}, from {} to {} {})", g3(median), su, g3(lowest),
                                             g3(highest), su);
    if (law.tested_stress) {
      const double lo = (*law.tested_stress)[0], hi = (*law.tested_stress)[1];
      const auto below = static_cast<std::size_t>(std::lower_bound(tau.begin(), tau.end(), lo) - tau.begin());
      const auto above = static_cast<std::size_t>(tau.end() - std::upper_bound(tau.begin(), tau.end(), hi));
      if (below + above > 0) {
        std::string where;
        if (median < lo) where = fmt::format("the median is {} below the lowest tested stress", times(lo, median));
        else if (median > hi) where = fmt::format("the median is {} above the highest tested stress", times(median, hi));
        else where = "the median lies within it";
        std::string parts;
        if (below > 0)
          parts += fmt::format("{} lie below it (down to {} below the lowest tested stress)", share(below),
                               times(lo, lowest));
        if (above > 0)
          parts += fmt::format("{}{} lie above it (up to {} above the highest tested stress)", parts.empty() ? "" : ", ",
                               share(above), times(highest, hi));
        out.push_back(fmt::format(
            "joint set '{}': {} (t = {:g} {}) the shear stresses of its locked contacts {} leave the range its law "
            "{} was tested at (tested_stress [{:g}, {:g}] {}): {}; {}. There the law's creep is an extrapolation of "
            "the data",
            js.name, when, time, s.units.time, stresses, law.name, lo, hi, su, parts, where));
      }
    }
    for (const auto& name : law.unidentified) {
      if (spec_of(law, name).unit != "stress") continue;
      const double threshold = law.parameters.at(name);
      const auto below = static_cast<std::size_t>(std::lower_bound(tau.begin(), tau.end(), threshold) - tau.begin());
      out.push_back(fmt::format(
          "joint set '{}': {} (t = {:g} {}) {} carry a shear stress below {} = {:g} {}, which "
          "the data do not determine (unidentified) {}: {}; the median is {} {} {}. Whether these contacts creep is "
          "decided by the choice of {}, not by the data",
          js.name, when, time, s.units.time, share(below), name, threshold, su, stresses,
          below == n  ? "they do not flow through its element"
          : below > 0 ? "those do not flow through its element, the others do"
                      : "every one flows through its element, at a rate set by the choice",
          median < threshold ? times(threshold, median) : times(median, threshold),
          median < threshold ? "below" : "above", name, name));
    }
  }
  return out;
}

}  // namespace rheodda::scene::detail
