// Reading what a case's run wrote: files as text, CSV lines and the series of
// one history.csv column, with its value at a time (docs/guide/studies.md).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "study_internal.hpp"

namespace rheodda::study {
namespace fs = std::filesystem;

namespace detail {

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream b;
  b << in.rdbuf();
  return b.str();
}

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> out;
  std::string cur;
  for (char ch : line) {
    if (ch == ',') {
      out.push_back(cur);
      cur.clear();
    } else if (ch != '\r') {
      cur += ch;
    }
  }
  out.push_back(cur);
  return out;
}

}  // namespace detail

using detail::split_csv_line;

std::vector<std::pair<double, double>> read_history_series(const std::string& history_csv, const std::string& column) {
  std::ifstream in(history_csv);
  if (!in) throw std::runtime_error(fmt::format("cannot read {}", history_csv));
  std::string line;
  std::vector<std::string> header;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    header = split_csv_line(line);
    break;
  }
  const auto col = [&](const std::string& name) -> int {
    for (std::size_t i = 0; i < header.size(); ++i)
      if (header[i] == name) return static_cast<int>(i);
    return -1;
  };
  const int it = col("time");
  int iu = col(column), iv = -1;
  // POINT.displacement = hypot(POINT.u, POINT.v); POINT.displacement_after_settling of
  // POINT.u_after_settling and POINT.v_after_settling (docs/reference/outputs.md).
  for (const std::string after : {"", "_after_settling"}) {
    const std::string suffix = ".displacement" + after;
    if (iu >= 0 || column.size() <= suffix.size() ||
        column.compare(column.size() - suffix.size(), suffix.size(), suffix) != 0)
      continue;
    const std::string point = column.substr(0, column.size() - suffix.size());
    iu = col(point + ".u" + after);
    iv = col(point + ".v" + after);
    if (iv < 0) iu = -1;
  }
  if (it < 0 || iu < 0) throw std::runtime_error(fmt::format("{} has no column '{}'", history_csv, column));
  std::vector<std::pair<double, double>> out;
  if (column == "stage") {
    // The stage in force is a name (docs/reference/stages.md); as a number: the stages begun so
    // far, 0 before the first. A step function: a stage begins between two steps, at the time
    // of the row before its first, which gets both values (value_at takes the later one after it).
    std::string current;
    double begun = 0.0;
    while (std::getline(in, line)) {
      if (line.empty() || line[0] == '#') continue;
      const auto f = split_csv_line(line);
      const std::string name = iu < static_cast<int>(f.size()) ? f[static_cast<std::size_t>(iu)] : std::string();
      const double t = std::stod(f.at(static_cast<std::size_t>(it)));
      if (!name.empty() && name != current && !out.empty()) out.emplace_back(out.back().first, begun + 1.0);
      if (!name.empty() && name != current) begun += 1.0, current = name;
      out.emplace_back(t, begun);
    }
    return out;
  }
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const auto f = split_csv_line(line);
    const auto at = [&](int i) { return i < static_cast<int>(f.size()) ? f[static_cast<std::size_t>(i)] : std::string(); };
    if (at(iu).empty() || (iv >= 0 && at(iv).empty())) continue;  // e.g. no closed contact at that time
    const double t = std::stod(at(it));
    const double u = std::stod(at(iu));
    out.emplace_back(t, iv >= 0 ? std::hypot(u, std::stod(at(iv))) : u);
  }
  return out;
}

std::optional<double> value_at(const std::vector<std::pair<double, double>>& s, double t) {
  if (s.empty() || t < s.front().first || t > s.back().first) {
    // Tolerate rounding of the last time (the run ends at its duration up to float addition).
    if (!s.empty() && std::abs(t - s.back().first) <= 1e-9 * std::max(1.0, std::abs(t))) return s.back().second;
    return std::nullopt;
  }
  for (std::size_t i = 1; i < s.size(); ++i)
    if (t <= s[i].first) {
      const auto [t0, v0] = s[i - 1];
      const auto [t1, v1] = s[i];
      if (t1 == t0) return v1;
      return v0 + (v1 - v0) * (t - t0) / (t1 - t0);  // linear interpolation between the two history rows
    }
  return s.back().second;
}

}  // namespace rheodda::study
