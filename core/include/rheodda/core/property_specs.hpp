// The properties of a block material (core::Material), of a bolt (core::BoltProperties,
// bolt.hpp) and of the water (core::WaterProperties, water.hpp) declared once: each by
// its scene word, unit, valid range, typed default and meaning, in the declaration type
// of the law parameters and the engine's settings (laws::SettingSpec, laws::ParameterSpec;
// settings.hpp declares core::Settings so), bound to its member.
//
// Everything that lists these properties reads them from here: the engine's range checks
// (check_declared: model_checks.cpp, bolt_checks.cpp, water_loads.cpp), the scene's keys of
// `materials:`, `bolts:` (and a stage's `add_bolts:`) and `water:` (scene/src/keys_joints.cpp,
// keys_bolts.cpp, keys_water.cpp take each key's unit, range, default and meaning from its
// declaration; the scene's Material, BoltDescription and WaterDescription are the structs
// declared here, which build_scene hands on whole), Python's Scene (through those keys), and
// the key tables of docs/reference/scene-format.md (generated from the keys).
//
// The default is the struct's (the member's initializer is the one place it is written);
// a default that is a mark outside the range says what it means ("never yields"). What
// ties properties together (a pretension within the yield force, a law's E1 and the bolt's
// axial_stiffness, damping only with dynamic steps) stays in the checks named above. A
// material's `plane` is a choice between words (laws::ChoiceSpec: material_choice_specs),
// declared here too; the scene's materials default to plane strain (scene::Material), the
// engine's to plane stress (Material{}), so the key's default is read from the scene's struct.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "rheodda/core/model.hpp"
#include "rheodda/laws/choice_spec.hpp"
#include "rheodda/laws/setting_spec.hpp"

namespace rheodda::core {

/// One property of a block material (name: the member of Material and the key of a
/// scene's `materials.NAME:` map).
using MaterialSpec = laws::SettingSpec<Material>;
/// One property of a bolt (name: the member of BoltProperties and the key of a bolt of `bolts:`).
using BoltSpec = laws::SettingSpec<BoltProperties>;
/// One property of the water (name: the member of WaterProperties and the key of `water:`).
using WaterSpec = laws::SettingSpec<WaterProperties>;

/// One choice of a block material (`plane`).
using MaterialChoiceSpec = laws::ChoiceSpec<Material>;

/// Every declared property of a material, in the order of the docs.
const std::vector<MaterialSpec>& material_specs();
/// Every declared choice of a material (`plane`: `strain` or `stress`).
const std::vector<MaterialChoiceSpec>& material_choice_specs();
/// Every declared property of a bolt, in the order of the docs.
const std::vector<BoltSpec>& bolt_specs();
/// Every declared property of the water, in the order of the docs.
const std::vector<WaterSpec>& water_specs();

/// The declaration of the property `name`; std::out_of_range if there is none.
const MaterialSpec& material_spec(std::string_view name);
const MaterialChoiceSpec& material_choice_spec(std::string_view name);
const BoltSpec& bolt_spec(std::string_view name);
const WaterSpec& water_spec(std::string_view name);

/// Throws ModelError(`entry`.NAME) for the first property of `s` that its declaration
/// (`specs`) does not admit, in the declaration's words: "-1 is not in (0, ∞) (stress)".
template <class S>
void check_declared(const std::vector<laws::SettingSpec<S>>& specs, const S& s, const ModelEntry& entry) {
  for (const laws::SettingSpec<S>& spec : specs)
    if (const double v = spec.value(s); !spec.admits(v))
      throw ModelError(entry, spec.name(), laws::setting_refusal(spec, v));
}

/// The same for a struct that is no entry of a list (the water): ModelError(`prefix`.NAME).
template <class S>
void check_declared(const std::vector<laws::SettingSpec<S>>& specs, const S& s, const std::string& prefix) {
  for (const laws::SettingSpec<S>& spec : specs)
    if (const double v = spec.value(s); !spec.admits(v))
      throw ModelError(prefix + "." + spec.name(), laws::setting_refusal(spec, v));
}

}  // namespace rheodda::core
