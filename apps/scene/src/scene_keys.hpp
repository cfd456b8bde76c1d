// The valid keys of every map of a scene file (scene_keys.cpp); those of `analysis:`
// and `analysis.settle` are declared with their types in keys.hpp.
#pragma once

#include <string>
#include <vector>

namespace rheodda::scene::detail::keys {
extern const std::vector<std::string> top;
extern const std::vector<std::string> units;
extern const std::vector<std::string> material;
extern const std::vector<std::string> joint_set;
extern const std::vector<std::string> law;
extern const std::vector<std::string> block;
extern const std::vector<std::string> rectangle;
extern const std::vector<std::string> grid;
extern const std::vector<std::string> rock_mass;
extern const std::vector<std::string> rock_mass_joint_set;
extern const std::vector<std::string> rock_mass_trace;
extern const std::vector<std::string> fixed_point;
extern const std::vector<std::string> load;
extern const std::vector<std::string> measurement_point;
extern const std::vector<std::string> water;
extern const std::vector<std::string> water_sample;
extern const std::vector<std::string> stage;
extern const std::vector<std::string> stage_remove_blocks;
extern const std::vector<std::string> stage_fixed_point;
extern const std::vector<std::string> stage_load;
extern const std::vector<std::string> stage_joint_set;
extern const std::vector<std::string> stage_analysis;
extern const std::vector<std::string> bolt;       // load_bolts.cpp
extern const std::vector<std::string> bolt_from;
extern const std::vector<std::string> bolt_to;
}  // namespace rheodda::scene::detail::keys
