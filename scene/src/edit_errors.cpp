// A refused edit's key in a scene's words (edits.hpp), from what the engine's
// ModelError says as data (its list entry), not from its text.
#include <string>
#include <utility>

#include "rheodda/scene/edits.hpp"

namespace rheodda::scene {

namespace {

/// The scene's name of an edit's list.
std::string scene_list(const std::string& list) {
  if (list == "add_point_loads") return "add_loads";
  if (list == "remove_point_loads") return "remove_loads";
  return list;
}

}  // namespace

std::string edit_key(const core::ModelError& e) {
  if (!e.entry()) return scene_list(e.key());  // a whole list or a setting
  const core::ModelEntry& at = *e.entry();
  std::string part = at.part;
  if (at.list == "add_bolts")  // a bolt's ends (core::Bolt a, b) are `from` and `to` in a scene
    for (const auto& [end, word] : {std::pair<std::string, std::string>{"a", "from"}, {"b", "to"}})
      if (part == end || part.rfind(end + ".", 0) == 0) part.replace(0, end.size(), word);
  return scene_list(at.list) + "[" + std::to_string(at.index) + "]" + (part.empty() ? "" : "." + part);
}

}  // namespace rheodda::scene
