// Shared data of the laws tests: the seed's Table 1 and the laws built from it.
#pragma once

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "rheodda/laws/registry.hpp"
#include "rheodda/laws/seed_table1.hpp"

namespace rheodda::laws::test {

/// The seed's Table 1 (laws/seed_table1.hpp): tau [MPa], E1 and E2 [MPa/mm],
/// eta1 and eta2 [MPa h/mm] of each row.
using Table1Row = SeedTable1Row;
inline const auto& table1() { return kSeedTable1; }

inline const std::vector<Scheme>& all_schemes() {
  static const std::vector<Scheme> s = {Scheme::lagged, Scheme::implicit,
                                        Scheme::exponential_linear};
  return s;
}

inline std::unique_ptr<ContactRheology> make(const std::string& name, const ParameterValues& p) {
  return LawRegistry::builtin().create(name, p);
}
inline std::unique_ptr<ContactRheology> burgers(const Table1Row& r) {
  return make("burgers", {{"E1", r.E1}, {"E2", r.E2}, {"eta1", r.eta1}, {"eta2", r.eta2}});
}
inline std::unique_ptr<ContactRheology> maxwell(const Table1Row& r) {
  return make("maxwell", {{"E1", r.E1}, {"eta1", r.eta1}});
}
inline std::unique_ptr<ContactRheology> kelvin(const Table1Row& r) {
  return make("kelvin", {{"E2", r.E2}, {"eta2", r.eta2}});
}
/// Nishihara from a Table 1 row: the Bingham viscosity eta3 takes eta1, threshold Fs.
inline std::unique_ptr<ContactRheology> nishihara(const Table1Row& r, double fs) {
  return make("nishihara",
              {{"E1", r.E1}, {"E2", r.E2}, {"eta2", r.eta2}, {"eta3", r.eta1}, {"Fs", fs}});
}
/// Generalized Kelvin from a Table 1 row: a second, slower Kelvin unit E3 = E2/2, eta3 = eta1.
inline std::unique_ptr<ContactRheology> generalized_kelvin(const Table1Row& r) {
  return make("generalized-kelvin", {{"E1", r.E1},
                                     {"E2", r.E2},
                                     {"eta2", r.eta2},
                                     {"E3", 0.5 * r.E2},
                                     {"eta3", r.eta1}});
}

/// Relative difference |a - b| / |b| (absolute when b = 0).
inline double rel(double a, double b) { return b == 0.0 ? std::abs(a) : std::abs(a - b) / std::abs(b); }

}  // namespace rheodda::laws::test
