// The valid keys of the maps not yet declared with their types (scene_keys.cpp): the top
// level, `units:` and `stages:`; the others are declared in keys.hpp.
#pragma once

#include <string>
#include <vector>

namespace rheodda::scene::detail::keys {
extern const std::vector<std::string> top;
extern const std::vector<std::string> units;
extern const std::vector<std::string> stage;
extern const std::vector<std::string> stage_remove_blocks;
extern const std::vector<std::string> stage_fixed_point;
extern const std::vector<std::string> stage_load;
extern const std::vector<std::string> stage_joint_set;
extern const std::vector<std::string> stage_analysis;
}  // namespace rheodda::scene::detail::keys
