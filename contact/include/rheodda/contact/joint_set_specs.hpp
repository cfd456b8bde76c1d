// The properties of a joint set (contact::JointProperties, joint_set.hpp) declared once:
// each by its scene word, unit, valid range, typed default and meaning, in the declaration
// type of the law parameters and the engine's settings (laws::ParameterSpec; core's
// settings.hpp declares core::Settings so), bound to its member of JointProperties.
//
// Everything that lists these properties reads them from here: the contact layer's range
// checks (check_joint_set: ContactSystem's constructor and set_joint_set), the scene's
// `joint_sets:` keys and a stage's `joint_sets:` changes (scene/src/keys_joints.cpp and
// keys_stages.cpp take each key's unit, range, default and meaning from its declaration;
// the scene's JointSetDescription is a JointProperties, which build_scene hands on whole),
// Python's rheodda.JointSet (its attributes, their docs and which of them it may change),
// and the key tables of docs/reference/scene-format.md (generated from the keys).
//
// The default is JointProperties{}'s (the member's initializer in joint_set.hpp is the one
// place it is written); an optional property that is unset by default says what acts
// instead (unset_meaning: "the penalty"). What ties properties together (a residual
// strength at most the peak, a law's E1 and shear_stiffness) is check_joint_set's.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "rheodda/contact/joint_set.hpp"
#include "rheodda/laws/parameters.hpp"

namespace rheodda::contact {

/// One property of JointProperties.
struct JointPropertySpec {
  /// name: the member of JointProperties and the key of a scene's `joint_sets.NAME:` map;
  /// unit ("–" for none), meaning (one table cell), range; default_value:
  /// JointProperties{}'s, none for an optional property unset by default.
  laws::ParameterSpec parameter;
  std::variant<double JointProperties::*, std::optional<double> JointProperties::*> field;
  /// What acts while an optional property is unset ("the penalty"); empty for a plain one.
  std::string unset_meaning{};
  /// May change between steps (a stage's `joint_sets:`, Python's JointSet setters).
  bool between_steps = false;

  const std::string& name() const { return parameter.name; }
  /// The value in `j`; none for an optional property that is unset.
  std::optional<double> value(const JointProperties& j) const;
  /// Sets the member in `j` to `v`.
  void set(JointProperties& j, double v) const;
  /// `v` is valid: finite and within the range.
  bool admits(double v) const;
  /// The valid range as the scene loader's messages write it: "[0, 90)", "(0, inf]".
  std::string range_text() const;
  /// The default as the docs state it: "0", or the unset meaning.
  std::string default_text() const;
};

/// Every declared property, in the order of the docs.
const std::vector<JointPropertySpec>& joint_property_specs();

/// The declaration of the property `name`; std::out_of_range if there is none.
const JointPropertySpec& joint_property_spec(std::string_view name);

/// Checks the joint set `js` (index `index` in the list given): every declared property
/// within its declared range, then what ties properties together (a residual strength at
/// most the peak; one elastic shear stiffness, a law's E1 or shear_stiffness). Throws
/// JointSetError naming the property (its message in the scene loader's words:
/// "-1 is out of range [0, inf] [stress]").
void check_joint_set(const JointSet& js, std::size_t index);

}  // namespace rheodda::contact
