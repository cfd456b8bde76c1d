// Sampling a fitted law's parameters, unit conversion, percentiles (forecast.hpp).
#include "rheodda/forecast/forecast.hpp"
#include "rheodda/fit/fit.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>

#include "rheodda/laws/registry.hpp"
#include "rheodda/units/units.hpp"
#include "rheodda/scene/error.hpp"

namespace rheodda::forecast {
namespace {

using scene::SceneError;

[[noreturn]] void bad(const std::string& file, const std::string& key, const std::string& msg) {
  throw SceneError(file, {}, key, msg);
}

/// Size of a unit label in SI (m, N, s); nullopt for a label not known.
/// A uniform draw in [0, 1) from the top 53 bits (the same on every platform).
double uniform01(std::mt19937_64& g) { return static_cast<double>(g() >> 11) * 0x1.0p-53; }

/// A standard normal draw (Box-Muller; the second value of the pair is dropped).
double normal01(std::mt19937_64& g) {
  const double u1 = 1.0 - uniform01(g);  // (0, 1]
  const double u2 = uniform01(g);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * 3.14159265358979323846 * u2);
}

/// The correlation of the identifiable parameters must be one: numbers in [-1, 1], 1 on
/// the diagonal, symmetric, positive semidefinite (to rounding: eigenvalues >= -1e-9 n).
/// A matrix that is not would be sampled from another covariance than the fit's
/// (draw_samples clips negative eigenvalues), silently.
void check_correlation(const FittedLaw& r, const std::string& path) {
  const std::size_t n = r.names.size();
  std::vector<std::size_t> id;
  for (std::size_t i = 0; i < n; ++i)
    if (r.identifiable[i]) id.push_back(i);
  const auto key = [&](std::size_t i, std::size_t k) { return fmt::format("fits[{}].correlation[{}][{}]", r.law, i, k); };
  constexpr double kRounding = 1e-9;
  Eigen::MatrixXd m(static_cast<Eigen::Index>(id.size()), static_cast<Eigen::Index>(id.size()));
  for (std::size_t a = 0; a < id.size(); ++a)
    for (std::size_t b = 0; b < id.size(); ++b) {
      const std::size_t i = id[a], k = id[b];
      const double v = r.correlation[i * n + k];
      if (!std::isfinite(v) || std::abs(v) > 1.0 + kRounding)
        bad(path, key(i, k),
            fmt::format("the correlation of {} and {} (both identifiable) must be a number in [-1, 1]", r.names[i], r.names[k]));
      if (i == k && std::abs(v - 1.0) > kRounding) bad(path, key(i, k), fmt::format("a correlation's diagonal is 1, not {}", v));
      if (std::abs(v - r.correlation[k * n + i]) > kRounding)
        bad(path, key(i, k), fmt::format("the correlation is not symmetric ({} and {} at [{}][{}])", v, r.correlation[k * n + i], k, i));
      m(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b)) = v;
    }
  if (id.empty()) return;
  const double smallest = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(m, Eigen::EigenvaluesOnly).eigenvalues().minCoeff();
  if (smallest < -kRounding * static_cast<double>(id.size()))
    bad(path, fmt::format("fits[{}].correlation", r.law),
        fmt::format("is not a correlation matrix: not positive semidefinite (smallest eigenvalue {:.3g})", smallest));
}

}  // namespace

FittedLaw read_fit_report(const std::string& path, const std::string& law) {
  std::ifstream in(path, std::ios::binary);
  if (!in) bad(path, "", fmt::format("cannot open {}: {}", path, std::strerror(errno)));
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const std::exception& e) {
    bad(path, "", fmt::format("not a `rheodda fit --json` report: {}", e.what()));
  }
  if (!j.is_object() || !j.contains("fits") || !j["fits"].is_array() || j["fits"].empty())
    bad(path, "fits", "not a `rheodda fit --json` report (no 'fits' list)");
  const std::string want = law.empty() ? j.value("best", std::string()) : law;
  const nlohmann::json* f = nullptr;
  std::vector<std::string> laws;
  for (const auto& x : j["fits"]) {
    laws.push_back(x.value("law", std::string()));
    if (laws.back() == want) f = &x;
  }
  if (f == nullptr)
    bad(path, "fits", fmt::format("the report has no fit of law '{}'; it has: {}", want, fmt::join(laws, ", ")));
  FittedLaw r;
  r.file = path;
  r.law = want;
  const laws::LawInfo* info = laws::LawRegistry::builtin().find(r.law);
  if (info == nullptr) bad(path, "fits[" + r.law + "].law", fmt::format("'{}' is not a law of this program", r.law));
  try {
    const auto& ps = f->at("parameters");
    for (const auto& p : ps) {
      r.names.push_back(p.at("name").get<std::string>());
      r.values.push_back(p.at("value").get<double>());
      r.units.push_back(p.value("unit", std::string()));
      r.identifiable.push_back(p.at("identifiable").get<bool>());
      const auto& se = p.at("std_error");
      const double s = se.is_number() ? se.get<double>() : 0.0;
      // The fit's standard error is the delta method on ln p: se(p) = p se(ln p).
      r.log_std.push_back(r.identifiable.back() && r.values.back() > 0 ? s / r.values.back() : 0.0);
      const auto spec = std::find_if(info->parameters.begin(), info->parameters.end(),
                                     [&](const laws::ParameterSpec& sp) { return sp.name == r.names.back(); });
      if (spec == info->parameters.end())
        bad(path, fmt::format("fits[{}].parameters.{}", r.law, r.names.back()), "not a parameter of the law");
      r.dimensions.push_back(spec->unit);
      if (!(r.values.back() >= 0) || !std::isfinite(r.values.back()))
        bad(path, fmt::format("fits[{}].parameters.{}.value", r.law, r.names.back()),
            "a fitted parameter must be a number >= 0 (the sampling is on its logarithm)");
      if (r.values.back() == 0) {  // no logarithm to draw: held at 0 (e.g. a Nishihara threshold Fs = 0)
        r.identifiable.back() = false;
        r.log_std.back() = 0.0;
      }
      // An identifiable parameter's spread must be known: no standard error (null), a
      // negative one or one that is not finite would sample nothing, or garbage.
      if (r.identifiable.back() && !(se.is_number() && std::isfinite(se.get<double>()) && se.get<double>() >= 0.0))
        bad(path, fmt::format("fits[{}].parameters.{}.std_error", r.law, r.names.back()),
            fmt::format("an identifiable parameter needs a standard error >= 0, got {}", se.dump()));
    }
    const std::size_t n = r.names.size();
    const auto& c = f->at("correlation");
    if (!c.is_array() || c.size() != n) bad(path, fmt::format("fits[{}].correlation", r.law), fmt::format("expected a {}x{} matrix", n, n));
    r.correlation.assign(n * n, std::numeric_limits<double>::quiet_NaN());
    for (std::size_t i = 0; i < n; ++i) {
      if (!c[i].is_array() || c[i].size() != n) bad(path, fmt::format("fits[{}].correlation[{}]", r.law, i), fmt::format("expected {} values", n));
      for (std::size_t k = 0; k < n; ++k)
        if (c[i][k].is_number()) r.correlation[i * n + k] = c[i][k].get<double>();
    }
    check_correlation(r, path);
    // The weight of evidence of each law of the report (band_coverage: the other laws its data support).
    r.rank_by = j.value("rank_by", std::string("bic"));
    std::vector<double> criterion;
    for (const auto& x : j["fits"]) {
      const auto c = x.find(r.rank_by);
      criterion.push_back(c != x.end() && c->is_number() ? c->get<double>() : std::numeric_limits<double>::infinity());
    }
    const std::vector<double> w = fit::model_weights(criterion);
    for (std::size_t i = 0; i < laws.size(); ++i) r.weights.emplace_back(laws[i], std::isfinite(w[i]) ? w[i] : 0.0);
    const auto& u = j.at("units");
    r.stress_unit = u.value("stress", std::string());
    r.length_unit = u.value("length", std::string());
    r.time_unit = u.value("time", std::string());
  } catch (const SceneError&) {
    throw;
  } catch (const std::exception& e) {
    bad(path, fmt::format("fits[{}]", r.law), fmt::format("not a `rheodda fit --json` report: {}", e.what()));
  }
  return r;
}

Samples draw_samples(const FittedLaw& fit, std::size_t count, std::uint64_t seed, const Unidentified& u) {
  const std::size_t n = fit.names.size();
  std::vector<std::size_t> id;  // identifiable parameters
  Samples s;
  for (std::size_t i = 0; i < n; ++i) {
    if (fit.identifiable[i]) id.push_back(i);
    else (u.spread > 1.0 && fit.values[i] > 0 ? s.spread : s.held).push_back(fit.names[i]);
  }
  // Covariance of the ln p of the identifiable parameters: C_ij = r_ij s_i s_j.
  const auto m = static_cast<Eigen::Index>(id.size());
  Eigen::MatrixXd cov(m, m);
  for (Eigen::Index a = 0; a < m; ++a)
    for (Eigen::Index b = 0; b < m; ++b) {
      const std::size_t i = id[static_cast<std::size_t>(a)], k = id[static_cast<std::size_t>(b)];
      double r = fit.correlation[i * n + k];
      if (!std::isfinite(r)) r = i == k ? 1.0 : 0.0;
      cov(a, b) = r * fit.log_std[i] * fit.log_std[k];
    }
  // cov = V diag(lambda) V^T; a draw is V diag(sqrt(max(lambda, 0))) z (a correlation of
  // +-1 to rounding leaves a tiny negative eigenvalue, which is a direction of no spread).
  Eigen::MatrixXd factor = Eigen::MatrixXd::Zero(m, m);
  if (m > 0) {
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(cov);
    factor = eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.0).cwiseSqrt().asDiagonal();
  }
  std::mt19937_64 g(seed);
  const auto& registry = laws::LawRegistry::builtin();
  while (s.accepted.size() < count) {
    if (s.drawn >= 100 * count)
      throw std::runtime_error(fmt::format("{} of {} draws of {} were rejected by the law's ranges; the fit's "
                                           "covariance is too wide for this law", s.drawn - s.accepted.size(),
                                           s.drawn, fit.law));
    Eigen::VectorXd z(m);
    for (Eigen::Index a = 0; a < m; ++a) z(a) = normal01(g);
    const Eigen::VectorXd dz = factor * z;
    laws::ParameterValues v;
    for (std::size_t i = 0; i < n; ++i) v[fit.names[i]] = fit.values[i];
    for (Eigen::Index a = 0; a < m; ++a) {
      const std::size_t i = id[static_cast<std::size_t>(a)];
      v[fit.names[i]] = std::exp(std::log(fit.values[i]) + dz(a));
    }
    for (std::size_t i = 0; i < n; ++i)
      if (!fit.identifiable[i] && u.spread > 1.0)  // log-uniform in [value/F, value*F]
        v[fit.names[i]] = fit.values[i] * std::exp((2.0 * uniform01(g) - 1.0) * std::log(u.spread));
    ++s.drawn;
    try {
      (void)registry.create(fit.law, v);  // the law's own ranges say what is physical
      s.accepted.push_back(std::move(v));
    } catch (const laws::LawError& e) {
      ++s.rejected[e.key().empty() ? e.what() : e.key() + " out of range"];
    }
  }
  return s;
}

double unit_factor(const std::string& dimension, const FittedLaw& fit, const std::string& length,
                   const std::string& force, const std::string& time) {
  const units::Base report{.length = fit.length_unit, .force = "", .time = fit.time_unit, .stress = fit.stress_unit};
  const units::Base scene{.length = length, .force = force, .time = time};
  try {
    return units::convert(1.0, units::unit_of(dimension, report), units::unit_of(dimension, scene));
  } catch (const units::UnitError& e) {
    throw std::invalid_argument(fmt::format("cannot convert the fit's {} ({}, {}, {}) to the scene's units ({}, {}, {}): {}",
                                            dimension, fit.stress_unit, fit.length_unit, fit.time_unit, force, length,
                                            time, e.what()));
  }
}

double percentile(std::vector<double>& v, double p) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  const double h = (static_cast<double>(v.size()) - 1.0) * p / 100.0;  // Hyndman & Fan definition 7
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (h - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

History read_history(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(fmt::format("cannot read {}", path));
  History h;
  std::string line;
  const auto split = [](const std::string& l) {
    std::vector<std::string> f;
    std::string cur;
    for (char ch : l) {
      if (ch == ',') { f.push_back(cur); cur.clear(); }
      else if (ch != '\r') cur += ch;
    }
    f.push_back(cur);
    return f;
  };
  while (std::getline(in, line)) {
    if (line.rfind("# units:", 0) == 0) h.units_line = line;
    if (line.empty() || line[0] == '#') continue;
    if (h.columns.empty()) {
      h.columns = split(line);
      continue;
    }
    const auto f = split(line);
    std::vector<double> row(h.columns.size(), std::numeric_limits<double>::quiet_NaN());
    for (std::size_t c = 0; c < f.size() && c < row.size(); ++c)
      if (!f[c].empty()) row[c] = std::stod(f[c]);
    h.rows.push_back(std::move(row));
  }
  return h;
}

double history_at(const History& h, std::size_t tc, std::size_t c, double t) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (h.rows.empty() || t < h.rows.front()[tc] || t > h.rows.back()[tc] * (1 + 1e-12)) return nan;
  for (std::size_t k = 1; k < h.rows.size(); ++k)
    if (t <= h.rows[k][tc]) {
      const double t0 = h.rows[k - 1][tc], t1 = h.rows[k][tc];
      // A row's own time (to round-off: an output time the steps ended on): its value (the row before may be empty).
      if (std::abs(t - t1) <= 1e-12 * std::max(1.0, std::abs(t1)) || t1 == t0) return h.rows[k][c];
      return h.rows[k - 1][c] + (h.rows[k][c] - h.rows[k - 1][c]) * (t - t0) / (t1 - t0);
    }
  return h.rows.back()[c];
}

}  // namespace rheodda::forecast
