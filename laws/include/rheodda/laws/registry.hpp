// The law registry: every law by name with its parameter schema and a factory.
// Adding a law = one class in laws/ plus one line in register_builtin_laws()
// (laws/src/registry.cpp); docs/reference/laws.md walks through an example.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "rheodda/laws/contact_rheology.hpp"
#include "rheodda/laws/parameters.hpp"

namespace rheodda::laws {

/// A registered law: what it is and how to build it.
struct LawInfo {
  std::string name;      ///< "burgers"
  std::string summary;   ///< one line: the elements in words
  std::string equation;  ///< the constant-force creep curve, in text
  std::vector<ParameterSpec> parameters;
  /// Builds the law from complete, validated values.
  std::function<std::unique_ptr<ContactRheology>(const ParameterValues&)> make;
  /// `rheodda fit` can fit it; false for the nonlinear laws (power-law,
  /// power-law-burgers, damage-burgers), whose fits are not written yet.
  bool fittable = true;
};

class LawRegistry {
 public:
  /// The registry holding the built-in laws.
  static const LawRegistry& builtin();

  /// Adds a law; throws std::logic_error on a duplicate name.
  void add(LawInfo info);
  /// The law of that name, or nullptr.
  const LawInfo* find(std::string_view name) const;
  /// The law of that name; throws LawError with a "did you mean" hint.
  const LawInfo& get(std::string_view name) const;
  /// All laws in registration order.
  const std::vector<LawInfo>& laws() const { return laws_; }
  /// Validates `values` against the law's schema and builds it; throws LawError.
  std::unique_ptr<ContactRheology> create(std::string_view name,
                                          const ParameterValues& values) const;

 private:
  std::vector<LawInfo> laws_;
};

/// Registers the built-in laws (one line per law).
void register_builtin_laws(LawRegistry& registry);

}  // namespace rheodda::laws
