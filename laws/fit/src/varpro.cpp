// Variable-projection search for the starts of a fit (varpro.hpp; docs/guide/fitting.md, "How the
// minimum is found"). Golub & Pereyra, SIAM J. Numer. Anal. 10 (1973) 413-432 and Inverse
// Problems 19 (2003) R1-R26: for fixed nonlinear parameters the optimal linear ones are the
// solution of a linear least-squares problem, so the sum of squares is searched over the
// nonlinear parameters only.
#include "varpro.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rheodda::fit::detail {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The points the search uses: all of them, or every stride-th point of each
// stage (its first and last always) when there are more than max_points.
struct Sample {
  std::vector<double> t, y;
  std::vector<std::size_t> stage;
};

Sample make_sample(const CreepData& d, double inv_scale, std::size_t max_points) {
  const std::size_t n = d.t.size();
  const std::size_t stride = n <= max_points ? 1 : (n + max_points - 1) / max_points;
  Sample s;
  for (std::size_t k = 0; k < d.stages.size(); ++k) {
    const auto& st = d.stages[k];
    for (std::size_t j = st.first; j < st.first + st.count; ++j)
      if ((j - st.first) % stride == 0 || j + 1 == st.first + st.count) {
        s.t.push_back(d.t[j]);
        s.y.push_back(d.displacement[j] * inv_scale);
        s.stage.push_back(k);
      }
  }
  return s;
}

// Basis columns at the sample points and their dot products, computed once each.
class Columns {
 public:
  explicit Columns(const std::vector<double>& y) : y_(y) {
    for (double v : y) yy_ += v * v;
  }
  int add(std::vector<double> col) {
    double m = 0.0;
    for (double v : col) m = std::max(m, std::abs(v));
    max_abs_.push_back(m);
    cols_.push_back(std::move(col));
    return static_cast<int>(cols_.size()) - 1;
  }
  void freeze() {
    const std::size_t m = cols_.size();
    gram_.assign(m * m, std::numeric_limits<double>::quiet_NaN());
    yc_.assign(m, std::numeric_limits<double>::quiet_NaN());
  }
  double dot(int a, int b) {
    const std::size_t m = cols_.size();
    double& g = gram_[static_cast<std::size_t>(a) * m + static_cast<std::size_t>(b)];
    if (std::isnan(g)) {
      double s = 0.0;
      const double* x = cols_[a].data();
      const double* z = cols_[b].data();
      for (std::size_t j = 0, n = y_.size(); j < n; ++j) s += x[j] * z[j];
      g = s;
      gram_[static_cast<std::size_t>(b) * m + static_cast<std::size_t>(a)] = s;
    }
    return g;
  }
  double doty(int a) {
    double& g = yc_[a];
    if (std::isnan(g)) {
      double s = 0.0;
      const double* x = cols_[a].data();
      for (std::size_t j = 0, n = y_.size(); j < n; ++j) s += x[j] * y_[j];
      g = s;
    }
    return g;
  }
  double yy() const { return yy_; }
  double max_abs(int a) const { return max_abs_[a]; }

 private:
  const std::vector<double>& y_;
  double yy_ = 0.0;
  std::vector<std::vector<double>> cols_;
  std::vector<double> max_abs_, gram_, yc_;
};

// A column of a reduced problem: ca * column a + cb * column b.
struct Combo {
  int a = -1;
  double ca = 1.0;
  int b = -1;
  double cb = 0.0;
};

// Least squares over the span of `cols` (normal equations, Cholesky; m <= 6).
// false when the columns are (numerically) dependent: that face is skipped,
// its optimum being reached on a face of lower dimension.
bool solve_reduced(Columns& C, const std::vector<Combo>& cols, std::vector<double>& z, double& rss) {
  const std::size_t m = cols.size();
  double G[6][6], r[6];
  auto dot = [&](const Combo& p, const Combo& q) {
    double s = p.ca * q.ca * C.dot(p.a, q.a);
    if (q.b >= 0) s += p.ca * q.cb * C.dot(p.a, q.b);
    if (p.b >= 0) {
      s += p.cb * q.ca * C.dot(p.b, q.a);
      if (q.b >= 0) s += p.cb * q.cb * C.dot(p.b, q.b);
    }
    return s;
  };
  for (std::size_t i = 0; i < m; ++i) {
    r[i] = cols[i].ca * C.doty(cols[i].a) + (cols[i].b >= 0 ? cols[i].cb * C.doty(cols[i].b) : 0.0);
    for (std::size_t j = 0; j <= i; ++j) G[i][j] = dot(cols[i], cols[j]);
  }
  // Cholesky G = L L^T in the lower triangle; a pivot below 1e-10 of its
  // diagonal entry means a column nearly in the span of the previous ones.
  for (std::size_t i = 0; i < m; ++i) {
    const double diag = G[i][i];
    for (std::size_t j = 0; j <= i; ++j) {
      double s = G[i][j];
      for (std::size_t k = 0; k < j; ++k) s -= G[i][k] * G[j][k];
      if (i == j) {
        if (!(s > 1e-10 * diag) || !(diag > 0)) return false;
        G[i][i] = std::sqrt(s);
      } else {
        G[i][j] = s / G[j][j];
      }
    }
  }
  z.assign(m, 0.0);
  double w[6];
  for (std::size_t i = 0; i < m; ++i) {
    double s = r[i];
    for (std::size_t k = 0; k < i; ++k) s -= G[i][k] * w[k];
    w[i] = s / G[i][i];
  }
  for (std::size_t i = m; i-- > 0;) {
    double s = w[i];
    for (std::size_t k = i + 1; k < m; ++k) s -= G[k][i] * z[k];
    z[i] = s / G[i][i];
  }
  // At the least-squares solution RSS = y.y - z.(A^T y).
  double zr = 0.0;
  for (std::size_t i = 0; i < m; ++i) zr += z[i] * r[i];
  rss = std::max(C.yy() - zr, 0.0);
  return true;
}

// The Bingham element for Fs in [lo, hi]: the stages with |F| >= hi flow, and
// its term is c*A - v*B (c = 1/eta3, v = Fs/eta3).
struct Interval {
  int A = -1, B = -1;
  double lo = 0.0, hi = 0.0;
  bool single_level = false;  // every flowing stage has |F| = hi: A = hi*B, only c (hi - Fs) shows
};

// Solution of the linear subproblem at one node.
struct Linear {
  double rss = kInf;
  std::vector<double> c;   // compliance of each simple group (0 when off)
  bool flow = false;       // Bingham element on
  double c3 = 0.0, fs = 0.0;
  int interval = -1;
};

// Exact minimum of |sum_g c_g col_g + Bingham - y|^2 with c_g >= 0 and the
// Bingham cone constraints: every face of the cone is tried (each simple
// group on or off; the Bingham element off, or on one interval with v = lo c,
// v = hi c or v free), the best feasible face solution wins. The unconstrained
// solution of a face is tried first: if feasible it is that face's optimum.
Linear solve_node(Columns& C, const std::vector<int>& simple, const std::vector<Interval>& intervals,
                  bool bingham) {
  Linear best;
  const std::size_t m = simple.size();
  best.c.assign(m, 0.0);
  std::vector<Combo> cols;
  std::vector<double> z;
  // option -1: Bingham off; otherwise interval*3 + {0 lo, 1 hi, 2 free}
  const int options = bingham ? static_cast<int>(intervals.size()) * 3 : 0;
  for (int opt = -1; opt < options; ++opt) {
    const Interval* iv = opt >= 0 ? &intervals[opt / 3] : nullptr;
    const int face = opt >= 0 ? opt % 3 : -1;
    for (unsigned mask = (1u << m) - 1;; --mask) {  // all groups on first
      cols.clear();
      for (std::size_t g = 0; g < m; ++g)
        if (mask & (1u << g)) cols.push_back({simple[g], 1.0});
      if (iv) {
        if (face == 0) cols.push_back({iv->A, 1.0, iv->B, -iv->lo});
        else if (face == 1) cols.push_back({iv->A, 1.0, iv->B, -iv->hi});
        else {
          cols.push_back({iv->A, 1.0});
          cols.push_back({iv->B, -1.0});
        }
      }
      double rss = kInf;
      if (!cols.empty() && solve_reduced(C, cols, z, rss) && rss < best.rss) {
        bool ok = true;
        std::size_t idx = 0;
        std::vector<double> c(m, 0.0);
        for (std::size_t g = 0; g < m; ++g)
          if (mask & (1u << g)) {
            ok = ok && z[idx] >= 0.0;
            c[g] = z[idx++];
          }
        double c3 = 0.0, fs = 0.0;
        if (iv) {
          c3 = z[idx];
          ok = ok && c3 >= 0.0;
          if (face == 0) fs = iv->lo;
          else if (face == 1) fs = iv->hi;
          else {
            const double v = z[idx + 1];
            ok = ok && v >= iv->lo * c3 && v <= iv->hi * c3 && c3 > 0.0;
            fs = c3 > 0.0 ? v / c3 : iv->lo;
          }
        }
        if (ok) {
          best.rss = rss;
          best.c = c;
          best.flow = iv != nullptr && c3 > 0.0;
          best.c3 = c3;
          best.fs = fs;
          best.interval = opt >= 0 ? opt / 3 : -1;
        }
      } else if (cols.empty() && C.yy() < best.rss) {
        best.rss = C.yy();
        best.c.assign(m, 0.0);
        best.flow = false;
      }
      if (mask == 0) break;
    }
  }
  return best;
}

// Kelvin column: sum_i dF_i (1 - exp(-(t - t_i)/tau)) (the seed's eq. 2 superposed, eqs. 4-6),
// the stages before the current one through S0 = sum_{i<k} dF_i exp(-(t_k - t_i)/tau),
// carried from stage to stage (as in residuals.cpp's evaluate_series): O(1) per point.
// 1 - e^-r directly: its rounding (eps/r relative) does not matter to the search.
std::vector<double> kelvin_column(const Sample& s, const std::vector<double>& st,
                                  const std::vector<double>& sf, double tau) {
  std::vector<double> col(s.t.size());
  double s0 = 0.0;
  std::size_t cur = 0;  // the stage S0 refers to
  for (std::size_t j = 0; j < s.t.size(); ++j) {
    const std::size_t k = s.stage[j];
    for (; cur < k; ++cur) {
      const double df = sf[cur] - (cur ? sf[cur - 1] : 0.0);
      s0 = std::exp(-(st[cur + 1] - st[cur]) / tau) * (s0 + df);
    }
    const double before = k ? sf[k - 1] : 0.0;
    const double ev = std::exp(-(s.t[j] - st[k]) / tau);
    col[j] = (sf[k] - before) * (1.0 - ev) + (before - ev * s0);
  }
  return col;
}

}  // namespace

namespace {

// The search itself: over the grid of retardation times, or at the given ones
// (`fixed_taus`, one per Kelvin element: a single node).
std::vector<VarProStart> search(const SeriesStructure& s, std::size_t np, const CreepData& data,
                                double inv_scale, const VarProSettings& settings, VarProStats* stats,
                                const std::vector<double>* fixed_taus) {
  std::vector<const Element*> kelvins;
  const Element* dashpot = nullptr;
  const Element* bingham = nullptr;
  for (const auto& el : s.elements) {
    if (el.kind == Kind::kelvin) kelvins.push_back(&el);
    else if (el.kind == Kind::dashpot) {
      if (dashpot) return {};
      dashpot = &el;
    } else {
      if (bingham) return {};
      bingham = &el;
    }
  }
  if (kelvins.size() > 2) return {};

  const Sample smp = make_sample(data, inv_scale, settings.max_points);
  const std::size_t ns = smp.t.size();
  std::vector<double> st, sf, flow_before;
  double flow = 0.0;
  for (std::size_t k = 0; k < data.stages.size(); ++k) {
    st.push_back(data.stages[k].t);
    sf.push_back(data.stages[k].stress);
    flow_before.push_back(flow);
    if (k + 1 < data.stages.size()) flow += sf[k] * (data.stages[k + 1].t - st[k]);
  }
  double ymax = 0.0;
  for (double v : smp.y) ymax = std::max(ymax, std::abs(v));

  Columns C(smp.y);
  std::vector<int> simple;        // base column of each simple group
  std::vector<int> simple_param;  // its compliance parameter (E or eta index)
  enum { spring_group, dashpot_group };
  int spring_col = -1, dash_col = -1;
  if (s.spring >= 0) {  // spring: F(t)
    std::vector<double> col(ns);
    for (std::size_t j = 0; j < ns; ++j) col[j] = sf[smp.stage[j]];
    spring_col = C.add(std::move(col));
  }
  if (dashpot) {  // dashpot: integral of F from 0 to t
    std::vector<double> col(ns);
    for (std::size_t j = 0; j < ns; ++j) {
      const std::size_t k = smp.stage[j];
      col[j] = flow_before[k] + sf[k] * (smp.t[j] - st[k]);
    }
    dash_col = C.add(std::move(col));
  }
  // Retardation-time grid: from a third of the shortest sampling interval to
  // ten times the test duration, per_decade nodes per decade (at most 120).
  std::vector<double> taus;
  std::vector<int> kcol;
  if (fixed_taus) {
    if (fixed_taus->size() != kelvins.size()) return {};
    taus = *fixed_taus;
    std::sort(taus.begin(), taus.end());
    for (double tau : taus) {
      if (!(tau > 0) || !std::isfinite(tau)) return {};
      kcol.push_back(C.add(kelvin_column(smp, st, sf, tau)));
    }
  } else if (!kelvins.empty()) {
    double gap = kInf;
    for (std::size_t j = 1; j < ns; ++j)
      if (smp.t[j] > smp.t[j - 1]) gap = std::min(gap, smp.t[j] - smp.t[j - 1]);
    const double span = smp.t.back() - st.front();
    if (!std::isfinite(gap) || !(span > 0)) return {};
    const double lo = gap / 3.0, hi = 10.0 * span;
    const int count = std::clamp(
        static_cast<int>(std::ceil(std::log10(hi / lo) * settings.per_decade)) + 1, 2, 120);
    for (int g = 0; g < count; ++g) {
      taus.push_back(lo * std::pow(hi / lo, static_cast<double>(g) / (count - 1)));
      kcol.push_back(C.add(kelvin_column(smp, st, sf, taus.back())));
    }
  }
  // Bingham intervals between the distinct stress levels |F| > 0.
  std::vector<Interval> intervals;
  double level_max = 0.0;
  if (bingham) {
    std::vector<double> levels;
    for (double f : sf)
      if (f != 0.0) levels.push_back(std::abs(f));
    std::sort(levels.begin(), levels.end());
    levels.erase(std::unique(levels.begin(), levels.end()), levels.end());
    if (levels.empty()) return {};
    level_max = levels.back();
    // More than 32 levels (a ramp recorded stage by stage): the intervals
    // between 33 quantiles of the levels; within one, A and B are taken for
    // the stages at or above its upper end (an approximation for the search only).
    std::vector<double> edges{0.0};
    if (levels.size() <= 32) edges.insert(edges.end(), levels.begin(), levels.end());
    else
      for (int q = 1; q <= 32; ++q) edges.push_back(levels[(levels.size() - 1) * q / 32]);
    for (std::size_t e = 1; e < edges.size(); ++e) {
      if (edges[e] <= edges[e - 1]) continue;
      Interval iv;
      iv.lo = edges[e - 1];
      iv.hi = edges[e];
      // Flowing stage i contributes sign(F_i)(|F_i| - Fs) dt_i: A = sum F_i dt_i, B = sum sign(F_i) dt_i.
      // Sums over the stages before the current one carried from stage to stage.
      std::vector<double> a(ns, 0.0), b(ns, 0.0);
      bool single = true;
      for (double f : sf)
        if (std::abs(f) >= iv.hi) single = single && std::abs(f) == iv.hi;
      double a_before = 0.0, b_before = 0.0;
      std::size_t cur = 0;
      for (std::size_t j = 0; j < ns; ++j) {
        const std::size_t k = smp.stage[j];
        for (; cur < k; ++cur)
          if (std::abs(sf[cur]) >= iv.hi) {
            a_before += sf[cur] * (st[cur + 1] - st[cur]);
            b_before += (sf[cur] > 0 ? 1.0 : -1.0) * (st[cur + 1] - st[cur]);
          }
        a[j] = a_before;
        b[j] = b_before;
        if (std::abs(sf[k]) >= iv.hi) {
          a[j] += sf[k] * (smp.t[j] - st[k]);
          b[j] += (sf[k] > 0 ? 1.0 : -1.0) * (smp.t[j] - st[k]);
        }
      }
      iv.single_level = single;
      iv.A = C.add(std::move(a));
      iv.B = C.add(std::move(b));
      intervals.push_back(iv);
    }
  }
  C.freeze();

  // Groups: spring, Kelvin elements (their columns change with the node), dashpot.
  const int kelvin_first = spring_col >= 0 ? 1 : 0;
  if (spring_col >= 0) simple.push_back(spring_col);
  for (std::size_t e = 0; e < kelvins.size(); ++e) simple.push_back(-1);
  if (dash_col >= 0) simple.push_back(dash_col);

  struct Node {
    std::vector<int> g;  // grid index of each Kelvin element
    Linear lin;
  };
  std::vector<Node> nodes;
  auto run = [&](std::vector<int> g) {
    for (std::size_t e = 0; e < g.size(); ++e) simple[kelvin_first + e] = kcol[g[e]];
    nodes.push_back({std::move(g), solve_node(C, simple, intervals, bingham != nullptr)});
  };
  const int ng = static_cast<int>(taus.size());
  if (kelvins.empty()) run({});
  else if (kelvins.size() == 1)
    for (int a = 0; a < ng; ++a) run({a});
  else
    for (int a = 0; a < ng; ++a)
      for (int b = a + 1; b < ng; ++b) run({a, b});
  if (stats) {
    stats->nodes = nodes.size();
    stats->points = ns;
  }

  // Local minima of the projected sum of squares over the grid (a node no
  // worse than its neighbours, index distance 1 in every Kelvin coordinate).
  std::vector<std::size_t> minima;
  if (kelvins.empty()) minima.push_back(0);
  else if (kelvins.size() == 1) {
    for (int a = 0; a < ng; ++a) {
      const double r = nodes[a].lin.rss;
      if ((a == 0 || r <= nodes[a - 1].lin.rss) && (a + 1 == ng || r <= nodes[a + 1].lin.rss))
        minima.push_back(static_cast<std::size_t>(a));
    }
  } else {
    std::vector<double> grid(static_cast<std::size_t>(ng) * ng, kInf);
    for (const auto& nd : nodes) grid[nd.g[0] * ng + nd.g[1]] = nd.lin.rss;
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      const int a = nodes[i].g[0], b = nodes[i].g[1];
      const double r = nodes[i].lin.rss;
      bool is_min = true;
      for (int da = -1; da <= 1 && is_min; ++da)
        for (int db = -1; db <= 1 && is_min; ++db) {
          const int x = a + da, y = b + db;
          if ((da == 0 && db == 0) || x < 0 || y >= ng || x >= y) continue;
          is_min = r <= grid[x * ng + y];
        }
      if (is_min) minima.push_back(i);
    }
  }
  std::stable_sort(minima.begin(), minima.end(),
                   [&](std::size_t p, std::size_t q) { return nodes[p].lin.rss < nodes[q].lin.rss; });
  if (minima.size() > static_cast<std::size_t>(settings.max_starts)) minima.resize(settings.max_starts);

  // A compliance at its bound 0 becomes one whose term is 1e-9 of the data's
  // scale: the parameter is then far out, and the Jacobian shows the data do
  // not depend on it.
  auto tiny = [&](int col) {
    const double m = C.max_abs(col);
    return m > 0 ? 1e-9 * ymax / m : 1e-9;
  };
  // The search works on displacements times inv_scale: its compliances are the
  // law's times inv_scale.
  const double unscale = 1.0 / inv_scale;
  std::vector<VarProStart> out;
  for (std::size_t idx : minima) {
    const Node& nd = nodes[idx];
    if (!std::isfinite(nd.lin.rss)) continue;
    VarProStart v;
    v.values.assign(np, 1.0);
    v.rss = nd.lin.rss;
    std::size_t g = 0;
    if (s.spring >= 0) {
      v.values[s.spring] = 1.0 / (unscale * std::max(nd.lin.c[g], tiny(spring_col)));
      ++g;
    }
    for (std::size_t e = 0; e < kelvins.size(); ++e, ++g) {
      const int col = kcol[nd.g[e]];
      const double E = 1.0 / (unscale * std::max(nd.lin.c[g], tiny(col)));
      v.values[kelvins[e]->E] = E;
      v.values[kelvins[e]->eta] = taus[nd.g[e]] * E;  // tau = eta/E
    }
    if (dashpot) v.values[dashpot->eta] = 1.0 / (unscale * std::max(nd.lin.c[g], tiny(dash_col)));
    if (bingham) {
      if (nd.lin.flow) {
        const Interval& iv = intervals[nd.lin.interval];
        double c3 = nd.lin.c3, fs = nd.lin.fs;
        if (iv.single_level) {
          // Only c (hi - Fs) is in the data: any Fs in [lo, hi) fits as well.
          // Take the middle, so that the fit's Jacobian shows both eta3 and Fs
          // in the direction the data do not fix.
          const double q = c3 * (iv.hi - fs);
          fs = 0.5 * (iv.lo + iv.hi);
          c3 = q / (iv.hi - fs);
        }
        fs = std::max(fs, 1e-6 * level_max);
        v.values[bingham->eta] = 1.0 / (unscale * c3);
        v.values[bingham->threshold] = fs;
      } else {
        // No flow: the threshold above every stress, the viscosity far out.
        v.values[bingham->threshold] = 1.5 * level_max;
        v.values[bingham->eta] = intervals.empty() ? 1e9 : 1.0 / (unscale * tiny(intervals.front().A));
      }
    }
    out.push_back(std::move(v));
  }
  return out;
}

}  // namespace

std::vector<VarProStart> varpro_starts(const SeriesStructure& s, std::size_t np,
                                       const CreepData& data, double inv_scale,
                                       const VarProSettings& settings, VarProStats* stats) {
  return search(s, np, data, inv_scale, settings, stats, nullptr);
}

bool varpro_refine(const SeriesStructure& s, const CreepData& data, double inv_scale,
                   std::vector<double>& values) {
  std::vector<double> taus;
  for (const auto& el : s.elements)
    if (el.kind == Kind::kelvin) taus.push_back(values[el.eta] / values[el.E]);
  VarProSettings all;
  all.max_points = data.t.size();
  all.max_starts = 1;
  auto out = search(s, values.size(), data, inv_scale, all, nullptr, &taus);
  if (out.empty()) return false;
  values = std::move(out.front().values);
  return true;
}

}  // namespace rheodda::fit::detail
