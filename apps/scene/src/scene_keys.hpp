// The valid keys of the maps not declared with their types (scene_keys.cpp): the top
// level and `units:`; the others are declared in keys.hpp.
#pragma once

#include <string>
#include <vector>

namespace rheodda::scene::detail::keys {
extern const std::vector<std::string> top;
extern const std::vector<std::string> units;
}  // namespace rheodda::scene::detail::keys
