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
  for (const std::string after : {"", "_after_settling"}) {
    const std::string u = ".u" + after;
    for (std::size_t c = 0; c < n; ++c) {
      const std::string name = h.columns[c];
      if (name.size() <= u.size() || name.compare(name.size() - u.size(), u.size(), u) != 0) continue;
      const std::string point = name.substr(0, name.size() - u.size());
      const auto v = std::find(h.columns.begin(), h.columns.end(), point + ".v" + after);
      if (v == h.columns.end()) continue;
      const auto cv = static_cast<std::size_t>(v - h.columns.begin());
      h.columns.push_back(point + ".displacement" + after);
      for (auto& row : h.rows) row.push_back(std::hypot(row[c], row[cv]));  // NaN (empty) before the settling's end
    }
  }
}

void write_bands(const std::string& path, const std::vector<History>& members, const std::vector<std::string>& columns,
                 const std::vector<double>& percentiles, const std::vector<double>& times) {
  const History& first = members.front();
  std::ofstream f(path, std::ios::binary);
  if (!first.units_line.empty()) f << first.units_line << "\n";
  f << "time";
  for (const auto& c : columns)
    for (double p : percentiles) f << fmt::format(",{}.p{:g}", c, p);
  f << ",members\n";
  // Each member's time column and the index of every banded column in it, found once.
  std::vector<std::size_t> time_column;
  std::vector<std::vector<std::optional<std::size_t>>> index(members.size());
  for (std::size_t m = 0; m < members.size(); ++m) {
    time_column.push_back(*column_index(members[m], "time"));
    for (const auto& c : columns) index[m].push_back(column_index(members[m], c));
  }
  for (const double t : times) {
    f << fmt::format("{}", t);
    std::size_t count = 0;
    for (std::size_t ci = 0; ci < columns.size(); ++ci) {
      std::vector<double> v;
      for (std::size_t m = 0; m < members.size(); ++m) {
        const auto hc = index[m][ci];
        if (!hc) continue;
        const double x = history_at(members[m], time_column[m], *hc, t);
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
