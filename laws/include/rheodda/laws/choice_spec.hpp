// A setting that is a choice between words, declared once beside the struct that owns it:
// its name (the scene word), its words (those of the method table of its values, in their
// order), its meaning (one table cell) and its default, the word of S{}'s value. The
// engine's choices (core/settings.hpp: choice_specs, settle_choice_specs) and the contact
// layer's (contact/contact_settings_specs.hpp: contact_choice_specs) are declared with it;
// the scene's keys of the same names are read from them (scene/src/keys.cpp).
#pragma once

#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace rheodda::laws {

/// One row of a table of words for the values of a choice that has no registry of its
/// own (the registries of core/methods.hpp have rows of the same shape).
template <class T>
struct ChoiceWord {
  T method;               ///< the value of the member
  std::string_view word;  ///< its scene word
};

/// One choice setting of the struct `S`.
template <class S>
struct ChoiceSpec {
  std::string key;                  ///< the member's scene word
  std::vector<std::string> words;   ///< the words a scene may give, in the docs' order
  std::string meaning;              ///< one table cell of the docs
  /// What the host says beside the default's word ("(the stage's steps are the
  /// analysis's kind)"); empty for none.
  std::string default_note{};
  /// The choice may change between two steps of a run (Python's Simulation.set_settings
  /// takes it, as SettingSpec::between_steps says of a number).
  bool between_steps = false;
  std::function<std::string(const S&)> word_of;              ///< the word of the member's value in `s`
  std::function<void(S&, const std::string&)> set;           ///< sets the member from one of `words`

  const std::string& name() const { return key; }
  /// The default: the word of S{}'s value.
  std::string default_word() const { return word_of(S{}); }
  /// The default as the docs state it: "`implicit`", with the host's note.
  std::string default_text() const {
    return "`" + default_word() + "`" + (default_note.empty() ? "" : " " + default_note);
  }
};

/// The declaration of the member `field` of S, named `name`, whose values and words are the
/// rows of `table` (each with `method` and `word`), in the table's order.
template <class S, class T, class Table>
ChoiceSpec<S> declare_choice(const char* name, const Table& table, T S::*field, const char* meaning) {
  std::vector<std::pair<T, std::string>> rows;
  for (const auto& r : table) rows.emplace_back(r.method, std::string(r.word));
  ChoiceSpec<S> c;
  c.key = name;
  c.meaning = meaning;
  for (const auto& r : rows) c.words.push_back(r.second);
  c.word_of = [rows, field, key = c.key](const S& s) -> std::string {
    for (const auto& [method, word] : rows)
      if (method == s.*field) return word;
    throw std::logic_error(key + ": a value without a word in its table");
  };
  c.set = [rows, field, key = c.key](S& s, const std::string& w) {
    for (const auto& [method, word] : rows)
      if (word == w) {
        s.*field = method;
        return;
      }
    throw std::invalid_argument(key + ": no value is named " + w);
  };
  return c;
}

}  // namespace rheodda::laws
