// `rheodda generate`: a scene's rock mass (`rock_mass:`, docs/guide/rockmass.md) written
// out as an explicit scene, every generated block a `polygon` with its
// `edge_joint_sets`, for inspection and editing.
// Sample runs:
//   rheodda generate examples/rockmass/jointed-slope.yaml -o out/jointed-slope-explicit.yaml
//   rheodda generate examples/rockmass/tunnel.yaml -o out/tunnel-explicit.yaml --plot
#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>

#include "commands.hpp"
#include "rheodda/scene/loader.hpp"
#include "rheodda/scene/output.hpp"
#include "rheodda/scene/plot.hpp"
#include "rheodda/scene/progress.hpp"

namespace rheodda::apps {

namespace {

struct GenerateOptions {
  std::string scene;
  std::string out;
  bool plot = false;
  bool quiet = false;
};

/// The scene text without `rock_mass:` and with the generated blocks under `blocks:`,
/// one flow map a line after the hand-written ones. Coordinates are written in the
/// shortest form that reads back to the same double (fmt's "{}", Ryu-like), names as
/// they are (the loader allows letters, digits, '_', '-' and '.' only: plain YAML), so
/// the explicit scene loads to the very same blocks (tests/rockmass/scene_test.cpp).
/// The block lines are formatted directly: yaml-cpp's emitter, and reading the file
/// back, took 28 of the 33 s `generate` spent on 93 000 blocks.
std::string explicit_scene(const scene::SceneDescription& s, const std::string& text) {
  YAML::Node root = YAML::Load(text);
  root.remove("rock_mass");
  const YAML::Node hand = YAML::Clone(root["blocks"]);  // (assigning root["blocks"] below rebinds a plain copy too)
  const std::string placeholder = "RHEODDA_GENERATED_BLOCKS";
  root["blocks"] = placeholder;
  YAML::Emitter head;
  const scene::RockMassDescription& r = *s.rock_mass;
  head << YAML::Comment(fmt::format("Written by `rheodda generate` from {}: rock_mass '{}' (seed {}) as {} explicit "
                                    "blocks; edges on the region's boundary carry joint set '{}'.",
                                    s.file, r.name, r.seed, r.block_count, s.joint_sets[r.boundary_joint_set].name))
       << YAML::Newline << root;
  std::string out = std::string(head.c_str()) + "\n";
  std::string blocks = "blocks:\n";
  if (hand.IsDefined() && hand.IsSequence())
    for (const auto& b : hand) {
      YAML::Emitter e;
      e << YAML::Flow << b;
      blocks += fmt::format("  - {}\n", e.c_str());
    }
  for (std::size_t i = r.first_block; i < r.first_block + r.block_count; ++i) {
    const scene::BlockDescription& b = s.blocks[i];
    blocks += fmt::format("  - {{name: {}, material: {}, polygon: [", b.name, s.materials[b.material].name);
    for (std::size_t k = 0; k < b.polygon.size(); ++k)
      blocks += fmt::format("{}[{}, {}]", k ? ", " : "", b.polygon[k][0], b.polygon[k][1]);
    blocks += "], edge_joint_sets: [";
    for (std::size_t k = 0; k < b.edge_joint_set.size(); ++k)
      blocks += fmt::format("{}{}", k ? ", " : "", s.joint_sets[b.edge_joint_set[k]].name);
    blocks += "]}\n";
  }
  const std::string line = "blocks: " + placeholder + "\n";
  const std::size_t at = out.find(line);
  if (at == std::string::npos || out.find(line, at + 1) != std::string::npos)
    throw std::runtime_error("generate: the scene's text could not be rewritten (its blocks: key)");
  return out.replace(at, line.size(), blocks);
}

}  // namespace

void add_generate_command(CLI::App& app) {
  auto o = std::make_shared<GenerateOptions>();
  auto* g = app.add_subcommand(
      "generate", "Cut a scene's rock mass (rock_mass:) into blocks and write them as an explicit scene");
  g->add_option("SCENE", o->scene, "Scene file with a rock_mass: section")->required();
  g->add_option("-o,--output", o->out, "Explicit scene to write (YAML)")->required();
  g->add_flag("--plot", o->plot, "Also draw the blocks, edges coloured by joint set, into OUTPUT-blocks.png (gnuplot)");
  add_quiet_flag(*g, o->quiet);
  g->callback([o] {
    require_readable(o->scene);
    scene::Progress display(o->quiet ? nullptr : stderr);  // docs/reference/cli.md, "Progress"
    std::optional<scene::ProgressPhase> phase(std::in_place, display,
                                              fmt::format("rheodda generate: cutting the rock mass of {}", o->scene));
    const scene::SceneDescription s = scene::load_scene(o->scene);
    if (!s.rock_mass)
      throw std::invalid_argument(fmt::format("{} has no rock_mass: section; nothing to generate", o->scene));
    phase.emplace(display, fmt::format("rheodda generate: writing {} ({} blocks)", o->out, s.blocks.size()));
    // The blocks were checked with the rock mass (as explicit blocks are); the text
    // reads back to them bit for bit (explicit_scene).
    const std::string text = explicit_scene(s, scene::read_scene_text(o->scene));
    const std::filesystem::path out(o->out);
    if (out.has_parent_path()) std::filesystem::create_directories(out.parent_path());
    scene::write_file_atomic(o->out, text);
    phase.reset();
    fmt::print("wrote {}: {} blocks ({} generated from rock_mass '{}')\n", o->out, s.blocks.size(),
               s.rock_mass->block_count, s.rock_mass->name);
    if (o->plot) {
      const std::string picture = (out.parent_path() / (out.stem().string() + "-blocks.png")).string();
      try {
        const scene::ProgressPhase drawing(display, fmt::format("rheodda generate: drawing {}", picture));
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
