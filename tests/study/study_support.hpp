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

#include "../scene/test_support.hpp"

namespace rheodda::study_test {

// The command-running, file and text helpers are the scene tests' own (../scene/test_support.hpp).
using test::CommandResult;
using test::fresh_dir;
using test::read_text;
using test::run_rheodda;
using test::spawn_rheodda;
using test::source_path;
using test::with;

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
