// The UDUNITS-2 side of units.hpp: the unit system read once, units parsed, converted and
// their dimension named. Every call into UDUNITS-2 holds `lock()` (the library keeps its
// parser's state and its status in globals).
#include "rheodda/units/units.hpp"

#include <udunits2.h>

#include <fmt/format.h>

#include <array>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace rheodda::units {

namespace {

std::mutex& lock() {
  static std::mutex m;
  return m;
}

struct UnitFree {
  void operator()(ut_unit* u) const { ut_free(u); }
};
struct ConverterFree {
  void operator()(cv_converter* c) const { cv_free(c); }
};
using UnitPtr = std::unique_ptr<ut_unit, UnitFree>;
using ConverterPtr = std::unique_ptr<cv_converter, ConverterFree>;

/// The unit system of UDUNITS-2's default database (UDUNITS2_XML_PATH or the installed
/// one), with `deg` (the arc degree, as rheodda writes angles) added. Call under lock().
ut_system* unit_system() {
  static ut_system* system = [] {
    ut_set_error_message_handler(ut_ignore);  // its messages on stderr: ours say it better
    ut_system* s = ut_read_xml(nullptr);
    if (!s)
      throw UnitError(fmt::format("cannot read UDUNITS-2's unit database (status {}; is libudunits2-data "
                                  "installed, or UDUNITS2_XML_PATH set to a wrong file?)",
                                  static_cast<int>(ut_get_status())));
    UnitPtr degree(ut_parse(s, "arc_degree", UT_ASCII));
    if (!degree || ut_map_symbol_to_unit("deg", UT_ASCII, degree.get()) != UT_SUCCESS)
      throw UnitError("cannot name the arc degree 'deg' in UDUNITS-2's unit system");
    return s;
  }();
  return system;
}

/// `text` parsed, or null when UDUNITS-2 does not know it. Call under lock().
UnitPtr parse(const std::string& text) {
  std::string t = text;
  return UnitPtr(ut_parse(unit_system(), ut_trim(t.data(), UT_UTF8), UT_UTF8));
}

UnitPtr parse_or_throw(const std::string& text) {
  if (text.empty()) return parse("1");
  UnitPtr u = parse(text);
  if (!u) throw UnitError(fmt::format("unknown unit '{}' (units as UDUNITS-2 writes them: m, mm, kN, MPa, kg/m^3, d, h, s, deg)", text));
  return u;
}

/// The exponents of a unit's base units: force, length, time, then the others.
struct Exponents {
  // SI base units by their symbols; mass is written as force*time^2/length.
  std::array<int, 8> power{};  // force, length, time, angle, current, temperature, amount, luminosity
};

constexpr std::array<const char*, 8> kWords{"force", "length", "time", "angle", "current", "temperature",
                                            "amount", "luminosity"};

void add_basic(const ut_unit* u, int p, Exponents& e) {
  const char* s = ut_get_symbol(u, UT_ASCII);
  const std::string sym = s ? s : "";
  if (sym == "kg") e.power[0] += p, e.power[1] -= p, e.power[2] += 2 * p;  // kg = N s^2 / m
  else if (sym == "m") e.power[1] += p;
  else if (sym == "s") e.power[2] += p;
  else if (sym == "rad") e.power[3] += p;
  else if (sym == "A") e.power[4] += p;
  else if (sym == "K") e.power[5] += p;
  else if (sym == "mol") e.power[6] += p;
  else if (sym == "cd") e.power[7] += p;
}

ut_status visit_basic(const ut_unit* u, void* arg) {
  add_basic(u, 1, *static_cast<Exponents*>(arg));
  return UT_SUCCESS;
}
ut_status visit_product(const ut_unit*, int count, const ut_unit* const* basics, const int* powers, void* arg) {
  for (int i = 0; i < count; ++i) add_basic(basics[i], powers[i], *static_cast<Exponents*>(arg));
  return UT_SUCCESS;
}
ut_status visit_galilean(const ut_unit*, double, const ut_unit* underlying, double, void* arg);
ut_status visit_timestamp(const ut_unit*, const ut_unit*, double, void*) { return UT_VISIT_ERROR; }
ut_status visit_logarithmic(const ut_unit*, double, const ut_unit*, void*) { return UT_VISIT_ERROR; }
const ut_visitor kVisitor{visit_basic, visit_product, visit_galilean, visit_timestamp, visit_logarithmic};
ut_status visit_galilean(const ut_unit*, double, const ut_unit* underlying, double, void* arg) {
  return ut_accept_visitor(underlying, &kVisitor, arg);
}

std::string words(const Exponents& e) {
  std::string num, den;
  for (std::size_t i = 0; i < kWords.size(); ++i) {
    const int p = e.power[i];
    if (p == 0) continue;
    std::string& side = p > 0 ? num : den;
    const int a = p > 0 ? p : -p;
    side += fmt::format("{}{}{}", side.empty() ? "" : (p > 0 ? "*" : "/"), kWords[i], a == 1 ? "" : fmt::format("^{}", a));
  }
  if (num.empty() && den.empty()) return "dimensionless";
  return (num.empty() ? "1" : num) + (den.empty() ? "" : "/" + den);
}

/// Under lock().
std::string dimension_of(const ut_unit* u) {
  Exponents e;
  if (ut_accept_visitor(u, &kVisitor, &e) != UT_SUCCESS) return "a time stamp or logarithmic unit";
  return words(e);
}

}  // namespace

bool known(const std::string& unit) {
  const std::lock_guard<std::mutex> g(lock());
  return static_cast<bool>(parse(unit.empty() ? "1" : unit));
}

bool convertible(const std::string& from, const std::string& to) {
  const std::lock_guard<std::mutex> g(lock());
  const UnitPtr a = parse(from.empty() ? "1" : from), b = parse(to.empty() ? "1" : to);
  return a && b && ut_are_convertible(a.get(), b.get());
}

double convert(double value, const std::string& from, const std::string& to) {
  const std::lock_guard<std::mutex> g(lock());
  const UnitPtr a = parse_or_throw(from), b = parse_or_throw(to);
  if (!ut_are_convertible(a.get(), b.get()))
    throw UnitError(fmt::format("{} is {}, not {}", from.empty() ? "a plain number" : from, dimension_of(a.get()),
                                dimension_of(b.get())));
  const ConverterPtr c(ut_get_converter(a.get(), b.get()));
  if (!c) throw UnitError(fmt::format("cannot convert {} to {} (UDUNITS-2 status {})", from, to, static_cast<int>(ut_get_status())));
  return cv_convert_double(c.get(), value);
}

std::string dimension_words(const std::string& unit) {
  const std::lock_guard<std::mutex> g(lock());
  return dimension_of(parse_or_throw(unit).get());
}

}  // namespace rheodda::units
