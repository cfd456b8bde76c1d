// `rheodda generate`: a scene's rock mass (`rock_mass:`, docs/rockmass.md) written
// out as an explicit scene, every generated block a `polygon` with its
// `edge_joint_sets`, for inspection and editing.
// Sample runs:
//   rheodda generate examples/rockmass/jointed-slope.yaml -o out/jointed-slope-explicit.yaml
//   rheodda generate examples/rockmass/tunnel.yaml -o out/tunnel-explicit.yaml --plot
#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <memory>
#include <stdexcept>

#include "commands.hpp"
#include "rheodda/scene/loader.hpp"
#include "rheodda/scene/output.hpp"
#include "rheodda/scene/plot.hpp"

namespace rheodda::apps {

namespace {

struct GenerateOptions {
  std::string scene;
  std::string out;
  bool plot = false;
};

/// The scene text without `rock_mass:` and with the generated blocks under `blocks:`.
/// Coordinates are written in the shortest form that reads back to the same double,
/// so the explicit scene loads to the very same blocks.
std::string explicit_scene(const scene::SceneDescription& s, const std::string& text) {
  YAML::Node root = YAML::Load(text);
  root.remove("rock_mass");
  YAML::Node blocks = root["blocks"];
  if (!blocks.IsDefined() || blocks.IsNull()) blocks = YAML::Node(YAML::NodeType::Sequence);
  const scene::RockMassDescription& r = *s.rock_mass;
  for (std::size_t i = r.first_block; i < r.first_block + r.block_count; ++i) {
    const scene::BlockDescription& b = s.blocks[i];
    YAML::Node block(YAML::NodeType::Map);
    block["name"] = b.name;
    block["material"] = s.materials[b.material].name;
    YAML::Node polygon(YAML::NodeType::Sequence);
    for (const auto& p : b.polygon) {
      YAML::Node xy(YAML::NodeType::Sequence);
      xy.push_back(fmt::format("{}", p[0]));
      xy.push_back(fmt::format("{}", p[1]));
      xy.SetStyle(YAML::EmitterStyle::Flow);
      polygon.push_back(xy);
    }
    polygon.SetStyle(YAML::EmitterStyle::Flow);
    block["polygon"] = polygon;
    YAML::Node sets(YAML::NodeType::Sequence);
    for (int js : b.edge_joint_set) sets.push_back(s.joint_sets[js].name);
    sets.SetStyle(YAML::EmitterStyle::Flow);
    block["edge_joint_sets"] = sets;
    block.SetStyle(YAML::EmitterStyle::Flow);
    blocks.push_back(block);
  }
  root["blocks"] = blocks;
  YAML::Emitter out;
  out << YAML::Comment(fmt::format("Written by `rheodda generate` from {}: rock_mass '{}' (seed {}) as {} explicit "
                                   "blocks; edges on the region's boundary carry joint set '{}'.",
                                   s.file, r.name, r.seed, r.block_count, s.joint_sets[r.boundary_joint_set].name))
      << YAML::Newline << root;
  return std::string(out.c_str()) + "\n";
}

}  // namespace

void add_generate_command(CLI::App& app) {
  auto o = std::make_shared<GenerateOptions>();
  auto* g = app.add_subcommand(
      "generate", "Cut a scene's rock mass (rock_mass:) into blocks and write them as an explicit scene");
  g->add_option("SCENE", o->scene, "Scene file with a rock_mass: section")->required();
  g->add_option("-o,--output", o->out, "Explicit scene to write (YAML)")->required();
  g->add_flag("--plot", o->plot, "Also draw the blocks, edges coloured by joint set, into OUTPUT-blocks.png (gnuplot)");
  g->callback([o] {
    require_readable(o->scene);
    const scene::SceneDescription s = scene::load_scene(o->scene);
    if (!s.rock_mass)
      throw std::invalid_argument(fmt::format("{} has no rock_mass: section; nothing to generate", o->scene));
    const std::string text = explicit_scene(s, scene::read_scene_text(o->scene));
    // The explicit scene must load to the same blocks (it is checked like any scene).
    const scene::SceneDescription back = scene::parse_scene(text, o->out);
    if (back.blocks.size() != s.blocks.size())
      throw std::runtime_error(fmt::format("the explicit scene reads back {} blocks, not {}", back.blocks.size(),
                                           s.blocks.size()));
    const std::filesystem::path out(o->out);
    if (out.has_parent_path()) std::filesystem::create_directories(out.parent_path());
    scene::write_file_atomic(o->out, text);
    fmt::print("wrote {}: {} blocks ({} generated from rock_mass '{}')\n", o->out, s.blocks.size(),
               s.rock_mass->block_count, s.rock_mass->name);
    if (o->plot) {
      const std::string picture = (out.parent_path() / (out.stem().string() + "-blocks.png")).string();
      try {
        scene::plot_scene(s, picture, "png");
      } catch (const std::runtime_error& e) {
        fmt::print(stderr, "rheodda: error: {}\n", e.what());
        throw CLI::RuntimeError(kExitFailure);
      }
      fmt::print("drew {}\n", picture);
    }
  });
}

}  // namespace rheodda::apps
