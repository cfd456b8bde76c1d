#include "rheodda/fit/creep_data.hpp"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <fmt/format.h>

namespace rheodda::fit {

namespace {

std::string describe(const std::string& file, std::size_t line, const std::string& column,
                     const std::string& message) {
  std::string where = file;
  if (line > 0) where += fmt::format(":{}", line);
  if (!column.empty()) where += fmt::format(": column '{}'", column);
  return fmt::format("{}: {}", where, message);
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  if (s.size() >= 2 && s.front() == '"' && s.back() == '"') s = s.substr(1, s.size() - 2);
  return s;
}

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> cells;
  std::size_t pos = 0;
  while (true) {
    const std::size_t comma = line.find(',', pos);
    cells.push_back(trim(line.substr(pos, comma == std::string_view::npos ? line.npos : comma - pos)));
    if (comma == std::string_view::npos) break;
    pos = comma + 1;
  }
  return cells;
}

std::string join(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace

DataError::DataError(std::string file, std::size_t line, std::string column,
                     const std::string& message)
    : std::runtime_error(describe(file, line, column, message)),
      file_(std::move(file)),
      line_(line),
      column_(std::move(column)) {}

CreepData parse_creep_csv(std::istream& in, const std::string& source, const CsvOptions& options) {
  const bool per_row = !options.stress_column.empty();
  if (!per_row && !options.stress)
    throw DataError(source, 0, "",
                    "no applied stress: give one stress for the file (--stress VALUE or "
                    "--stress T:V,...) or a stress column (--stress-column NAME)");

  CreepData data;
  data.source = source;
  data.time_column = options.time_column;
  data.displacement_column = options.displacement_column;
  data.stress_column = options.stress_column;
  data.sigma_column = options.sigma_column;
  const bool weighted = !options.sigma_column.empty();

  std::string text;
  std::size_t line_no = 0;
  std::vector<std::string> header;
  std::size_t col_t = 0, col_d = 0, col_s = 0, col_sigma = 0;
  std::vector<double> row_stress;

  auto find_column = [&](const std::string& name, const char* flag) {
    for (std::size_t i = 0; i < header.size(); ++i)
      if (header[i] == name) return i;
    throw DataError(source, line_no, name,
                    fmt::format("no such column in the header (set it with {}); columns: {}", flag,
                                join(header)));
  };

  while (std::getline(in, text)) {
    ++line_no;
    const std::string_view stripped = trim(text);
    if (stripped.empty() || stripped.front() == '#') continue;
    const auto cells = split(text);
    if (header.empty()) {
      for (const auto c : cells) header.emplace_back(c);
      if (header[0].rfind("\xEF\xBB\xBF", 0) == 0) header[0].erase(0, 3);  // UTF-8 byte order mark
      col_t = find_column(options.time_column, "--time-column");
      col_d = find_column(options.displacement_column, "--displacement-column");
      if (per_row) col_s = find_column(options.stress_column, "--stress-column");
      if (weighted) col_sigma = find_column(options.sigma_column, "--sigma-column");
      continue;
    }
    if (cells.size() != header.size())
      throw DataError(source, line_no, "",
                      fmt::format("{} cells, but the header names {} columns", cells.size(),
                                  header.size()));
    auto number = [&](std::size_t col) {
      const std::string_view cell = cells[col];
      double v = 0.0;
      const auto [p, ec] = std::from_chars(cell.data(), cell.data() + cell.size(), v);
      if (cell.empty() || ec != std::errc() || p != cell.data() + cell.size())
        throw DataError(source, line_no, header[col],
                        fmt::format("'{}' is not a number", cell));
      if (!std::isfinite(v))
        throw DataError(source, line_no, header[col],
                        fmt::format("'{}' is not a finite number", cell));
      // A least-squares fit squares and sums the values: beyond 1e150 (or below
      // 1e-150 but not 0) its sums overflow (or underflow) a double.
      if (v != 0.0 && !(std::abs(v) < 1e150 && std::abs(v) > 1e-150))
        throw DataError(source, line_no, header[col],
                        fmt::format("{:g} is out of the range a fit can square and sum (1e-150 to 1e150 in "
                                    "magnitude): change the unit of this column",
                                    v));
      return v;
    };
    const double t = number(col_t);
    const double d = number(col_d);
    if (t < 0.0)
      throw DataError(source, line_no, header[col_t],
                      fmt::format("time {:g} is negative; time is measured from the first loading",
                                  t));
    if (!data.t.empty() && t <= data.t.back())
      throw DataError(source, line_no, header[col_t],
                      fmt::format("time {:g} does not increase (previous row: {:g})", t,
                                  data.t.back()));
    data.t.push_back(t);
    data.displacement.push_back(d);
    data.line.push_back(line_no);
    if (per_row) row_stress.push_back(number(col_s));
    if (weighted) {
      const double sigma = number(col_sigma);
      if (!(sigma > 0.0))
        throw DataError(source, line_no, header[col_sigma],
                        fmt::format("sigma {:g} is not positive; a measurement standard deviation is > 0", sigma));
      data.sigma.push_back(sigma);
    }
  }
  if (header.empty()) throw DataError(source, 0, "", "empty file: no header row and no data");
  if (data.t.empty()) throw DataError(source, 0, "", "no data rows after the header");

  // Stages: from the stress column (a new stage at each change of value, the
  // first one from t = 0) or from the staged history of the file.
  if (per_row) {
    std::vector<laws::StagedHistory::Stage> stages{{0.0, row_stress[0]}};
    for (std::size_t i = 1; i < row_stress.size(); ++i)
      if (row_stress[i] != row_stress[i - 1]) stages.push_back({data.t[i], row_stress[i]});
    data.history = laws::StagedHistory(std::move(stages));
  } else {
    data.history = *options.stress;
  }

  const auto& hs = data.history.stages();
  const std::string stress_name = per_row ? options.stress_column : std::string("--stress");
  if (hs.empty()) throw DataError(source, 0, stress_name, "the stress history has no stage");
  if (data.t.front() < hs.front().t)
    throw DataError(source, data.line.front(), options.time_column,
                    fmt::format("time {:g} is before the first stress stage (starts at {:g}); the "
                                "first stage must start at or before the first row",
                                data.t.front(), hs.front().t));
  std::size_t j = 0;
  for (std::size_t i = 0; i < hs.size(); ++i) {
    StageInfo s{hs[i].t, hs[i].value, j, 0};
    const double end = i + 1 < hs.size() ? hs[i + 1].t : INFINITY;
    while (j < data.t.size() && data.t[j] < end) ++j;
    s.count = j - s.first;
    if (s.count == 0)
      throw DataError(source, 0, stress_name,
                      fmt::format("stage {} (stress {:g} from t = {:g}) has no data points", i + 1,
                                  s.stress, s.t));
    data.stages.push_back(s);
  }
  return data;
}

CreepData read_creep_csv(const std::filesystem::path& path, const CsvOptions& options) {
  // A folder, a device (/dev/zero would be read forever) or a pipe is not a data
  // file; nor is a file larger than any creep record (1 GB: 3e7 rows).
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!ec && std::filesystem::exists(status)) {
    if (std::filesystem::is_directory(status))
      throw DataError(path.string(), 0, "", "is a folder, not a CSV file");
    if (!std::filesystem::is_regular_file(status))
      throw DataError(path.string(), 0, "", "is not a regular file (a device or a pipe?): give a CSV file");
    constexpr std::uintmax_t kMaxBytes = 1ull << 30;
    if (const auto size = std::filesystem::file_size(path, ec); !ec && size > kMaxBytes)
      throw DataError(path.string(), 0, "",
                      fmt::format("is {} MB; creep data files above {} MB are refused", size >> 20, kMaxBytes >> 20));
  }
  std::ifstream in(path);
  if (!in) throw DataError(path.string(), 0, "", "cannot open the file for reading");
  return parse_creep_csv(in, path.string(), options);
}

}  // namespace rheodda::fit
