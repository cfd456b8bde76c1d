// The declaration of a name in a list of declarations (core/settings.cpp,
// contact/joint_set_specs.cpp, contact/contact_settings_specs.cpp).
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace rheodda::laws {

/// The declaration named `name` in `specs` (each with name()); std::out_of_range if there
/// is none, naming `owner` and what it declares ("core::Settings declares no setting NAME").
template <class Spec>
const Spec& spec_named(const std::vector<Spec>& specs, std::string_view name, const std::string& owner,
                       const std::string& what) {
  for (const Spec& s : specs)
    if (s.name() == name) return s;
  throw std::out_of_range(owner + " declares no " + what + " " + std::string(name));
}

}  // namespace rheodda::laws
