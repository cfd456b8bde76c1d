// Sub-commands of the rheodda program. Each family lives in its own file and
// registers itself on the CLI11 application; main.cpp only wires them up.
#pragma once

#include <CLI/CLI.hpp>

namespace rheodda::apps {

/// Exit codes: 0 success, 1 run-time failure, 2 bad input (arguments, files, parameters).
inline constexpr int kExitBadInput = 2;

/// `rheodda law list`, `rheodda law curve`.
void add_law_commands(CLI::App& app);

/// `rheodda check`, `rheodda run`, `rheodda plot` (apps/run_commands.cpp).
void add_scene_commands(CLI::App& app);

/// `rheodda fit`: fit laws to laboratory creep curves (apps/fit_command.cpp).
void add_fit_command(CLI::App& app);

/// `rheodda study`: a base scene's variations run as parallel cases (apps/study_command.cpp).
void add_study_command(CLI::App& app);

}  // namespace rheodda::apps
