// The ensemble's histories as `rheodda forecast` reports them (bands.hpp).
#include "rheodda/forecast/bands.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>

namespace rheodda::forecast {

std::optional<std::size_t> column_index(const History& h, const std::string& name) {
  const auto it = std::find(h.columns.begin(), h.columns.end(), name);
  if (it == h.columns.end()) return std::nullopt;
  return static_cast<std::size_t>(it - h.columns.begin());
}

void add_point_displacements(History& h) {
  const std::size_t n = h.columns.size();
  for (std::size_t c = 0; c < n; ++c) {
    const std::string& name = h.columns[c];
    if (name.size() < 3 || name.substr(name.size() - 2) != ".u") continue;
    const std::string point = name.substr(0, name.size() - 2);
    const auto v = std::find(h.columns.begin(), h.columns.end(), point + ".v");
    if (v == h.columns.end()) continue;
    const auto cv = static_cast<std::size_t>(v - h.columns.begin());
    h.columns.push_back(point + ".displacement");
    for (auto& row : h.rows) row.push_back(std::hypot(row[c], row[cv]));
  }
}

void write_bands(const std::string& path, const std::vector<History>& members, const std::vector<std::string>& columns,
                 const std::vector<double>& percentiles) {
  const History& first = members.front();
  const std::size_t tc = *column_index(first, "time");
  std::ofstream f(path, std::ios::binary);
  if (!first.units_line.empty()) f << first.units_line << "\n";
  f << "time";
  for (const auto& c : columns)
    for (double p : percentiles) f << fmt::format(",{}.p{:g}", c, p);
  f << ",members\n";
  for (const auto& row : first.rows) {
    const double t = row[tc];
    f << fmt::format("{}", t);
    std::size_t count = 0;
    for (const auto& c : columns) {
      std::vector<double> v;
      for (const auto& h : members) {
        const auto hc = column_index(h, c);
        if (!hc) continue;
        const double x = history_at(h, *column_index(h, "time"), *hc, t);
        if (std::isfinite(x)) v.push_back(x);
      }
      count = std::max(count, v.size());
      for (double p : percentiles) {
        std::vector<double> w = v;
        f << "," << (w.empty() ? std::string() : fmt::format("{}", percentile(w, p)));
      }
    }
    f << "," << count << "\n";
  }
}

Exceedance exceedance(const std::vector<History>& members, const std::string& column, double threshold, double by) {
  Exceedance e;
  for (const auto& h : members) {
    const auto hc = column_index(h, column);
    const std::size_t ht = *column_index(h, "time");
    double peak = -std::numeric_limits<double>::infinity();
    for (const auto& row : h.rows)
      if (row[ht] <= by * (1 + 1e-12) && std::isfinite(row[*hc])) peak = std::max(peak, row[*hc]);
    const double at_by = history_at(h, ht, *hc, by);
    if (std::isfinite(at_by)) peak = std::max(peak, at_by);
    ++e.members;
    e.exceeding += peak > threshold;
  }
  e.probability = static_cast<double>(e.exceeding) / static_cast<double>(e.members);
  e.std_error = std::sqrt(e.probability * (1 - e.probability) / static_cast<double>(e.members));
  return e;
}

}  // namespace rheodda::forecast
