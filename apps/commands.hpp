// Sub-commands of the rheodda program. Each family lives in its own file and
// registers itself on the CLI11 application; main.cpp only wires them up.
#pragma once

#include <CLI/CLI.hpp>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>

#include "rheodda/scene/quantity.hpp"

namespace rheodda::apps {

/// SIGINT and SIGTERM call `handler` (which records the signal for the command to
/// stop between two steps) instead of ending the process.
inline void on_stop_signals(void (*handler)(int)) {
  struct sigaction sa {};
  sa.sa_handler = handler;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

/// Exit codes: 0 success, 1 run-time failure, 2 bad input (arguments, files, parameters),
/// 3 step controls too coarse (check --refine),
/// 128 + N a run stopped by signal N. `rheodda --help` lists them (kExitCodesHelp), each command's
/// help in one line (kExitCodesLine).
inline constexpr int kExitFailure = 1;
inline constexpr int kExitBadInput = 2;
/// `rheodda check --refine`: the scene's step controls are coarser than the tolerance,
/// or its refinement did not converge (docs/guide/choosing-step-controls.md).
inline constexpr int kExitStepControls = 3;

/// The exit codes as `rheodda --help` prints them; each line says where the code comes from.
inline constexpr const char* kExitCodesHelp =
    "Exit codes:\n"
    "  0      success\n"
    "  1      the command failed while working: a run stopped by an engine or output error,\n"
    "         a study or forecast with a failed case, gnuplot missing or failing (plot, fit --plot),\n"
    "         a law curve that cannot hold its --tolerance or leaves the range of a double\n"
    "  2      bad input: command-line arguments, a file that cannot be opened, a scene, study\n"
    "         or data file refused (file:line:column: key: message), law parameters,\n"
    "         a directory that holds no run (plot), --resume on another scene\n"
    "  3      check --refine: the scene's step controls are coarser than the tolerance,\n"
    "         or its refinement study does not converge\n"
    "  128+N  a run stopped by signal N between two steps (130: Ctrl-C, 143: kill);\n"
    "         continue it with `rheodda run SCENE -o OUTDIR --resume`";

/// The line each command's help ends with instead of the whole list.
inline constexpr const char* kExitCodesLine =
    "Exit codes: 0 success, 1 failure, 2 bad input, 3 coarse step controls, 128+N signal N (`rheodda --help`)";

/// The number an option gives for a scene (`--until 100 d`): bare in the scene's units, or
/// with its unit, converted (scene::scene_number); the error names the option.
inline double option_quantity(const std::string& option, const std::string& text, const std::string& dimension,
                              const scene::Units& units) {
  try {
    return scene::scene_number(text, dimension, units);
  } catch (const scene::QuantityError& e) {
    throw std::invalid_argument(option + ": " + e.what());
  }
}

/// Throws std::invalid_argument("cannot open PATH: <reason>") unless the file at `path`
/// can be opened for reading (so that a missing file is reported by name, without a location).
inline void require_readable(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::invalid_argument("cannot open " + path + ": " + std::strerror(errno));
}

/// `-q,--quiet`: no progress on stderr (docs/reference/cli.md, "Progress").
inline void add_quiet_flag(CLI::App& command, bool& quiet) {
  command.add_flag("-q,--quiet", quiet,
                   "Show no progress (by default on stderr: a line redrawn on a terminal, else a line every 10 s)");
}

/// `rheodda law list`, `rheodda law curve`.
void add_law_commands(CLI::App& app);

/// `rheodda keys` (apps/keys_command.cpp): the declared scene keys, as text or Markdown tables.
void add_keys_command(CLI::App& app);

/// `rheodda check` (apps/check_command.cpp): a scene validated and described; with
/// --refine, its step controls measured by a refinement study.
void add_check_command(CLI::App& app);

/// `rheodda run`, `rheodda plot` (apps/run_commands.cpp).
void add_scene_commands(CLI::App& app);

/// `rheodda fit`: fit laws to laboratory creep curves (apps/fit_command.cpp).
void add_fit_command(CLI::App& app);

/// `rheodda study`: a base scene's variations run as parallel cases (apps/study_command.cpp).
void add_study_command(CLI::App& app);

/// `rheodda generate`: a scene's rock mass written as an explicit scene (apps/generate_command.cpp).
void add_generate_command(CLI::App& app);

/// `rheodda forecast`: a scene with the uncertainty of a fitted law (apps/forecast_command.cpp).
void add_forecast_command(CLI::App& app);

}  // namespace rheodda::apps
