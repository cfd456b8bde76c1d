// Helpers of the study tests: running the rheodda binary, temporary folders, study.csv.
#pragma once

#include <boost/test/unit_test.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace rheodda::study_test {

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

/// Runs the rheodda binary with `args` (shell words).
inline CommandResult run_rheodda(const std::string& args) {
  const std::string cmd = std::string(RHEODDA_BINARY) + " " + args + " 2>&1";
  CommandResult r;
  FILE* p = ::popen(cmd.c_str(), "r");
  char buf[4096];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) r.output.append(buf, n);
  const int status = ::pclose(p);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

/// A fresh empty directory under the system temp dir.
inline std::filesystem::path fresh_dir(const std::string& name) {
  auto d = std::filesystem::temp_directory_path() / ("rheodda-study-test-" + name + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

/// `text` with the first occurrence of `from` replaced by `to` (which must exist).
inline std::string with(const std::string& from, const std::string& to, std::string text) {
  const auto at = text.find(from);
  BOOST_TEST_REQUIRE(at != std::string::npos, "fragment '" << from << "' not in the text");
  text.replace(at, from.size(), to);
  return text;
}

/// study.csv as rows of column -> text (no quoting inside the tests' values).
inline std::vector<std::map<std::string, std::string>> read_study_csv(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
  const auto split = [](const std::string& l) {
    std::vector<std::string> f;
    std::string cur;
    bool quoted = false;
    for (char ch : l) {
      if (ch == '"') quoted = !quoted;
      else if (ch == ',' && !quoted) { f.push_back(cur); cur.clear(); }
      else cur += ch;
    }
    f.push_back(cur);
    return f;
  };
  if (!std::getline(in, line)) return rows;
  header = split(line);
  while (std::getline(in, line)) {
    const auto f = split(line);
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < header.size() && i < f.size(); ++i) row[header[i]] = f[i];
    rows.push_back(row);
  }
  return rows;
}

}  // namespace rheodda::study_test
