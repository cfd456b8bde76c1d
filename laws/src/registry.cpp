#include "rheodda/laws/registry.hpp"

#include <fmt/format.h>

#include "rheodda/laws/builtin_laws.hpp"
#include "rheodda/laws/power_law.hpp"

namespace rheodda::laws {

void register_builtin_laws(LawRegistry& registry) {
  // One line per law: this is the only place a new law is announced.
  registry.add(Burgers::info());
  registry.add(Maxwell::info());
  registry.add(Kelvin::info());
  registry.add(Nishihara::info());
  registry.add(GeneralizedKelvin::info());
  registry.add(PowerLaw::info());
  registry.add(PowerLawBurgers::info());
  registry.add(DamageBurgers::info());
}

const LawRegistry& LawRegistry::builtin() {
  static const LawRegistry instance = [] {
    LawRegistry r;
    register_builtin_laws(r);
    return r;
  }();
  return instance;
}

void LawRegistry::add(LawInfo info) {
  if (find(info.name)) throw std::logic_error("law '" + info.name + "' registered twice");
  laws_.push_back(std::move(info));
}

const LawInfo* LawRegistry::find(std::string_view name) const {
  for (const auto& l : laws_)
    if (l.name == name) return &l;
  return nullptr;
}

const LawInfo& LawRegistry::get(std::string_view name) const {
  if (const LawInfo* l = find(name)) return *l;
  std::vector<std::string> names;
  for (const auto& l : laws_) names.push_back(l.name);
  const std::string hint = nearest_name(name, names);
  throw LawError("law", fmt::format("unknown law '{}'{}; known laws: {}", name,
                                    hint.empty() ? "" : fmt::format(" (did you mean '{}'?)", hint),
                                    fmt::join(names, ", ")));
}

std::unique_ptr<ContactRheology> LawRegistry::create(std::string_view name,
                                                     const ParameterValues& values) const {
  const LawInfo& info = get(name);
  return info.make(validate_parameters(info.name, info.parameters, values));
}

}  // namespace rheodda::laws
