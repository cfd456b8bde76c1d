// Helpers shared by the scene, study, rock-mass, forecast, units and command tests:
// a valid base scene, error expectations, running the command.
#pragma once

#include <boost/test/unit_test.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <vector>

#include "rheodda/scene/error.hpp"
#include "rheodda/scene/loader.hpp"

extern char** environ;  // the process environment, passed to spawned runs

namespace rheodda::test {

/// A small valid scene; line numbers below (1-based) are relied on by the tests.
inline const std::string kBaseScene =
    "units: {length: m, force: N, time: s}\n"                                     // 1
    "analysis:\n"                                                                 // 2
    "  duration: 1\n"                                                             // 3
    "  dt: 0.01\n"                                                                // 4
    "  gravity: [0, -9.81]\n"                                                     // 5
    "materials:\n"                                                                // 6
    "  rock: {density: 2600, young_modulus: 1.0e9, poisson_ratio: 0.25}\n"        // 7
    "joint_sets:\n"                                                               // 8
    "  bedding: {friction_angle: 30}\n"                                           // 9
    "  fault: {friction_angle: 20, law: {name: burgers, E1: 1, E2: 2, eta1: 3, eta2: 4}}\n"  // 10
    "blocks:\n"                                                                   // 11
    "  - {name: base, rectangle: {x: 0, y: 0, width: 4, height: 1}, joint_set: bedding, fixed: true}\n"  // 12
    "  - {name: top, polygon: [[1, 1], [2, 1], [2, 2], [1, 2]], edge_joint_sets: [fault, bedding, bedding, bedding]}\n"  // 13
    "measurement_points:\n"                                                       // 14
    "  - {name: p, point: [1.5, 1.5]}\n";                                         // 15

/// kBaseScene with the first occurrence of `from` replaced by `to` (which must exist).
inline std::string with(const std::string& from, const std::string& to, std::string text = kBaseScene) {
  const auto at = text.find(from);
  BOOST_TEST_REQUIRE(at != std::string::npos, "fragment '" << from << "' not in the scene");
  text.replace(at, from.size(), to);
  return text;
}

/// Parsing `text` must fail with a SceneError at (line, column) whose key and message hold the given parts.
inline void expect_error(const std::string& text, int line, int column, const std::string& key_part,
                         const std::string& message_part) {
  try {
    (void)scene::parse_scene(text, "bad.yaml");
    BOOST_ERROR("no error for a scene expected to fail with '" << message_part << "'");
  } catch (const scene::SceneError& e) {
    BOOST_TEST_INFO("error: " << e.what());
    BOOST_TEST(e.file() == "bad.yaml");
    BOOST_TEST(e.line() == line);
    if (column > 0) BOOST_TEST(e.column() == column);
    BOOST_TEST(e.key().find(key_part) != std::string::npos);
    BOOST_TEST(e.message().find(message_part) != std::string::npos);
    BOOST_TEST(std::string(e.what()).find("bad.yaml:" + std::to_string(line) + ":") == 0);
  }
}

/// Column (1-based) of the first `token` on line `line` of `text`.
inline int column_of(const std::string& text, int line, const std::string& token) {
  std::istringstream in(text);
  std::string l;
  for (int i = 0; i < line; ++i) std::getline(in, l);
  const auto at = l.find(token);
  BOOST_TEST_REQUIRE(at != std::string::npos, "token '" << token << "' not on line " << line);
  return static_cast<int>(at) + 1;
}

/// As expect_error, the column being that of `token` on `line`.
inline void expect_error_at(const std::string& text, int line, const std::string& token, const std::string& key_part,
                            const std::string& message_part) {
  expect_error(text, line, column_of(text, line, token), key_part, message_part);
}

inline std::string source_path(const std::string& rel) { return std::string(RHEODDA_SOURCE_DIR) + "/" + rel; }

inline std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream b;
  b << in.rdbuf();
  return b.str();
}

struct CommandResult {
  int exit_code = -1;
  std::string output;  ///< stdout and stderr
};

/// Runs the rheodda binary with `args` (shell words, already quoted as needed).
/// Runs a shell command line, stdout and stderr together.
inline CommandResult run_command(const std::string& command_line) {
  const std::string cmd = command_line + " 2>&1";
  CommandResult r;
  FILE* p = ::popen(cmd.c_str(), "r");
  char buf[4096];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) r.output.append(buf, n);
  const int status = ::pclose(p);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

/// `rheodda ARGS`, stdout and stderr together.
inline CommandResult run_rheodda(const std::string& args) {
  return run_command(std::string(RHEODDA_BINARY) + " " + args);
}

/// Starts the rheodda binary with `args` in the background, its output discarded;
/// returns its process id (for tests that signal or kill a run mid-way).
inline pid_t spawn_rheodda(std::vector<std::string> args) {
  std::string bin = RHEODDA_BINARY;
  std::vector<char*> argv{bin.data()};
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&fa, 2, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, bin.c_str(), &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  BOOST_TEST_REQUIRE(rc == 0, "cannot start " << bin);
  return pid;
}

/// A fresh empty directory under the system temp dir.
inline std::filesystem::path fresh_dir(const std::string& name) {
  auto d = std::filesystem::temp_directory_path() / ("rheodda-apps-test-" + name + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

}  // namespace rheodda::test
