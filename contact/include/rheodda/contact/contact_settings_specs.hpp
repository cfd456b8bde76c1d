// The contact layer's numerical settings that a host sets from its input
// (contact::ContactSettings, joint_set.hpp) declared once: each by its scene word, unit,
// valid range, typed default and meaning, as core::Settings's are (core/settings.hpp: one
// declaration type, laws::SettingSpec), bound to its member of ContactSettings.
//
// What reads them: ContactSystem's constructor (check_contact_setting_ranges), the scene's
// `analysis:` keys of the same names (scene/src/keys.cpp takes each key's unit, range,
// default and meaning from its declaration and reads into the member: the scene's
// Analysis is a ContactSettings, which build_scene hands on whole), and the key table of
// docs/reference/scene-format.md (generated from the keys).
//
// The default is ContactSettings{}'s (the member's initializer in joint_set.hpp is the one
// place it is written); `penalty`'s is a mark (0) that the host replaces by its own rule.
//
// Not declared here: what a host decides rather than takes from its user
// (min_search_distance, lock_at_touch, reversal_at_normal_resolution,
// stick_keeps_force_dynamic), the Newton settings of nonlinear laws (creep_newton_tolerance,
// max_creep_newton: no scene key). The scheme, a choice, is declared here in laws::ChoiceSpec
// (contact_choice_specs: its words, meaning, and ContactSettings{}'s value as its default). stick_keeps_force's default in a
// scene depends on the analysis (its declaration's host_default says how; the scene's loader
// applies it); ContactSettings{}'s is Shi's rule.
#pragma once

#include <string_view>
#include <vector>

#include "rheodda/contact/joint_set.hpp"
#include "rheodda/laws/choice_spec.hpp"
#include "rheodda/laws/setting_spec.hpp"

namespace rheodda::contact {

/// One declared setting of ContactSettings.
using ContactSettingSpec = laws::SettingSpec<ContactSettings>;

/// Every declared setting, in the order of the docs.
const std::vector<ContactSettingSpec>& contact_setting_specs();

/// The declaration of the setting `name`; std::out_of_range if there is none.
const ContactSettingSpec& contact_setting_spec(std::string_view name);

/// A choice of ContactSettings (the scheme): its scene word, words, meaning and default.
using ContactChoiceSpec = laws::ChoiceSpec<ContactSettings>;

/// Every declared choice of ContactSettings, in the order of the docs.
const std::vector<ContactChoiceSpec>& contact_choice_specs();

/// The declaration of the choice `name`; std::out_of_range if there is none.
const ContactChoiceSpec& contact_choice_spec(std::string_view name);

/// Throws std::invalid_argument("contact setting NAME: MESSAGE") for the first declared
/// setting of `s` that its declaration does not admit (ContactSystem's constructor); a
/// penalty left at its mark (0) is refused there on its own.
void check_contact_setting_ranges(const ContactSettings& s);

}  // namespace rheodda::contact
