// A study's record: study.csv (the cases' values) and study.json (what redraws it) (docs/guide/studies.md).
#include <fmt/format.h>

#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>

#include "study_internal.hpp"

namespace rheodda::study::detail {
namespace fs = std::filesystem;
namespace {

std::string csv_quote(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char ch : s) {
    if (ch == '"') q += '"';
    q += ch == '\n' ? ' ' : ch;
  }
  return q + "\"";
}

}  // namespace

// Shortest text that reads back as the same double: study.csv holds the runs' values exactly.
std::string format_value(double v) { return fmt::format("{}", v); }

std::string output_column(const std::string& output, double t) {
  const std::string g = fmt::format("{:g}", t);
  return output + "@" + (std::strtod(g.c_str(), nullptr) == t ? g : format_value(t));
}

void write_study_csv(const StudyDescription& study, const std::vector<CaseResult>& results, const fs::path& path) {
  std::ofstream out(path, std::ios::binary);
  out << "case,status";
  for (const auto& p : study.parameters) out << "," << p.name << " [" << p.unit << "]";
  for (const auto& o : study.outputs)
    for (double t : study.times) out << "," << csv_quote(output_column(o, t));
  out << ",wall_seconds,steps,inertia_share,message\n";
  for (std::size_t c = 0; c < results.size(); ++c) {
    const auto& r = results[c];
    out << csv_quote(r.name) << "," << r.status;
    const auto& pv = study.cases[c].parameter_values;
    for (std::size_t i = 0; i < study.parameters.size(); ++i) out << "," << (i < pv.size() ? format_value(pv[i]) : "");
    for (const auto& v : r.values) out << "," << (v ? format_value(*v) : "");
    out << "," << fmt::format("{:.3f}", r.wall_seconds) << "," << r.steps << ","
        << (r.inertia_share ? format_value(*r.inertia_share) : "") << "," << csv_quote(r.message) << "\n";
  }
}

/// study.json: what `rheodda plot OUTDIR` needs besides study.csv to redraw a study.
void write_study_json(const StudyDescription& study, const fs::path& path) {
  using nlohmann::json;
  json ps = json::array();
  for (const auto& p : study.parameters)
    ps.push_back({{"name", p.name}, {"key", p.key}, {"unit", p.unit}, {"scale", p.log_scale ? "log" : "linear"},
                  {"values", p.values}});
  json cases = json::array();
  for (const auto& c : study.cases) cases.push_back({{"name", c.name}, {"parameter_values", c.parameter_values}});
  const char* method = study.method == SweepMethod::grid ? "grid"
                       : study.method == SweepMethod::random ? "random" : "latin_hypercube";
  const json j{{"study", study.file}, {"title", study.title}, {"scene", study.scene}, {"outputs", study.outputs},
               {"times", study.times}, {"plot", study.plot}, {"method", method}, {"samples", study.samples},
               {"seed", study.seed}, {"parameters", ps}, {"cases", cases}};
  std::ofstream(path, std::ios::binary) << j.dump(2) << "\n";
}

}  // namespace rheodda::study::detail
