// An engine's and its contact system's state as bytes (rheodda/scene/saved_state.hpp):
// a checkpoint's state file (checkpoint_state.cpp) without the run's totals.
#include "rheodda/scene/saved_state.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "checkpoint_state.hpp"
#include "rheodda/scene/output.hpp"

namespace rheodda::scene {
namespace {

std::string text_hash(const std::string& text) { return fmt::format("{:016x}", fnv1a(text.data(), text.size())); }

}  // namespace

std::string encode_snapshot(const EngineSnapshot& s, const std::string& scene_text, std::size_t joint_sets) {
  // The totals are a run's (summary.json): a snapshot carries empty ones.
  return encode_state({s.engine, s.contacts, RunTotals(joint_sets, false)}, text_hash(scene_text));
}

EngineSnapshot decode_snapshot(const std::string& bytes, const std::string& what, const std::string& scene_text) {
  SavedRun run;
  try {
    run = decode_state(bytes, what, text_hash(scene_text));
  } catch (const std::invalid_argument& e) {
    // decode_state speaks to `rheodda run --resume`: keep its reason, not its advice.
    std::string m = e.what();
    const std::string prefix = "--resume: ";
    if (m.rfind(prefix, 0) == 0) m.erase(0, prefix.size());
    if (const std::size_t k = m.find("; nothing was changed"); k != std::string::npos) m.erase(k);
    throw std::invalid_argument(m);
  }
  return {std::move(run.engine), std::move(run.contacts)};
}

}  // namespace rheodda::scene
