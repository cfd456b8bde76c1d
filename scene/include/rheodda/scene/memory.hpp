// The memory a run of a scene will need, estimated before it starts, and the
// memory this process may use: `rheodda check` prints both, `rheodda run`
// refuses a scene that will not fit (docs/notes/performance.md, "Memory").
#pragma once

#include <optional>
#include <string>

#include "rheodda/scene/scene.hpp"

namespace rheodda::scene {

struct MemoryEstimate {
  double bytes = 0.0;   ///< estimated peak resident memory of `rheodda run` [bytes]
  std::string solver;   ///< the linear solver the estimate assumes (automatic resolved)
};

/// Peak resident memory of a run of `scene`, from its block count and solver:
/// a per-block cost measured on running-bond and stacked walls of 1e4 and 1e5
/// blocks (docs/notes/performance.md, "Memory"), an upper estimate within about 1.5x.
MemoryEstimate estimate_memory(const SceneDescription& scene);

/// The memory this process may still use [bytes]: the smallest of the system's
/// MemAvailable (/proc/meminfo), the control group's limit (memory.max less
/// memory.current) and the address-space limit (ulimit -v); none if unknown.
std::optional<double> available_memory();

/// "1.2 GB", "350 MB" (decimal units).
std::string format_bytes(double bytes);

}  // namespace rheodda::scene
