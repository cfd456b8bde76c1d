// The run's guards (docs/reference/outputs.md, "Runs that stop"): a run that will not fit
// in memory is refused before it starts; a state or output row that is no
// longer finite, and unbounded motion or output (analysis.max_travel_ratio,
// max_output_size), stop it instead of filling the disk.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "rheodda/scene/memory.hpp"
#include "run_internal.hpp"

namespace rheodda::scene {

void check_memory(const SceneDescription& s) {
  if (const auto available = available_memory()) {
    const MemoryEstimate need = estimate_memory(s);
    if (need.bytes > *available)
      throw std::runtime_error(fmt::format(
          "{}: the run needs about {} of memory ({} blocks, solver {}) but this process may use only {} "
          "(MemAvailable, the control group's limit, ulimit -v); run it where more memory is free{}",
          s.file, format_bytes(need.bytes), s.blocks.size(), need.solver, format_bytes(*available),
          need.solver == "cholmod" ? ", or with `solver: amg` (less memory for large models)" : ""));
  }
}

/// The first non-finite quantity of the engine's state ("velocity of block 'b3'"), or "".
std::string nonfinite_state(const core::Engine& e, const SceneDescription& s) {
  auto finite = [](const auto& v) {
    for (int i = 0; i < v.size(); ++i)
      if (!std::isfinite(v[i])) return false;
    return true;
  };
  if (!std::isfinite(e.time())) return "the time";
  for (int b = 0; b < e.block_count(); ++b) {
    const core::BlockState& st = e.block(b);
    for (const auto& v : st.vertices)
      if (!finite(v)) return fmt::format("a vertex position of block '{}'", s.blocks[b].name);
    if (!finite(st.velocity)) return fmt::format("the velocity of block '{}'", s.blocks[b].name);
    if (!finite(st.stress)) return fmt::format("the stress of block '{}'", s.blocks[b].name);
  }
  return "";
}

/// The name of the first column of a CSV row holding nan or inf, or "" (a number
/// written with {:g} contains neither 'n' nor 'i' unless it is not finite).
std::string nonfinite_column(const std::string& header, const std::string& row) {
  if (row.find_first_of("ni") == std::string::npos) return "";
  std::size_t h = 0, r = 0;
  while (r < row.size()) {
    const std::size_t re = std::min(row.find(',', r), row.find('\n', r));
    const std::size_t he = std::min(header.find(',', h), header.find('\n', h));
    const std::string cell = row.substr(r, re - r);
    if (cell.find_first_of("ni") != std::string::npos) return header.substr(h, he - h);
    if (re == std::string::npos || row[re] == '\n') break;
    r = re + 1;
    h = he == std::string::npos ? header.size() : he + 1;
  }
  return "a column";
}

double model_size(const std::vector<std::vector<core::Vec2>>& vertices) {
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (const auto& b : vertices)
    for (const auto& v : b) {
      x0 = std::min(x0, v.x()), x1 = std::max(x1, v.x());
      y0 = std::min(y0, v.y()), y1 = std::max(y1, v.y());
    }
  return std::max(x1 - x0, y1 - y0);
}

void check_guards(const Run& run, const core::Engine& e) {
  const SceneDescription& s = run.s;
  const Analysis& a = run.a;
  if (a.max_travel_ratio > 0.0) {
    const double limit = a.max_travel_ratio * run.model_size;
    for (int b = 0; b < e.block_count(); ++b) {
      const auto v = e.vertices(b);
      for (std::size_t k = 0; k < v.size(); ++k) {
        const double d = (v[k] - run.initial[b][k]).norm();
        if (d > limit)
          throw GuardTripped(fmt::format(
              "block '{}' has moved {:g} {}, more than max_travel_ratio ({:g}) x the model size ({:g} {}): the "
              "motion looks unbounded (no friction, a near-zero viscosity, an unsupported block?); check the "
              "scene, or raise analysis.max_travel_ratio (0 = no limit) to let it go on",
              s.blocks[b].name, d, s.units.length, a.max_travel_ratio, run.model_size, s.units.length,
              s.units.length));
      }
    }
  }
  if (a.max_output_size > 0.0) {
    const double mb = double(run.history.bytes() + run.contacts_csv.bytes() + run.frames_bytes) / 1e6;
    if (mb > a.max_output_size)
      throw GuardTripped(fmt::format(
          "the outputs have grown to {:.0f} MB, more than max_output_size ({:g} MB); raise "
          "analysis.max_output_size (0 = no limit) or output_interval",
          mb, a.max_output_size));
  }
}

}  // namespace rheodda::scene
