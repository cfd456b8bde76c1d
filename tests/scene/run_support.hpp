// Running a scene from the tests of `rheodda run` (run_test.cpp, resume_test.cpp,
// reliability_test.cpp): into a folder, stopped after a number of steps or
// resumed, through the library as the command does.
#pragma once

#include <filesystem>

#include "test_support.hpp"
#include "rheodda/scene/loader.hpp"
#include "rheodda/scene/run.hpp"

namespace rheodda::test {

/// Runs `s` (its file's text hashed for the checkpoint) into `out`; stopped once
/// `stop_after` steps are accepted (>= 0), or resumed from the checkpoint there.
inline scene::RunResult run(const scene::SceneDescription& s, const std::filesystem::path& out, int stop_after = -1,
                            bool resume = false) {
  scene::RunOptions o;
  o.out_dir = out.string();
  o.stop_after_step = stop_after;
  o.resume = resume;
  return scene::run_scene(s, read_text(s.file), o);
}

/// examples/sliding-block.yaml run for `duration` with frames every `interval` [s].
inline scene::SceneDescription sliding(double duration, double interval) {
  auto s = scene::load_scene(source_path("examples/sliding-block.yaml"));
  s.analysis.duration = duration;
  s.analysis.output_interval = interval;
  return s;
}

}  // namespace rheodda::test
