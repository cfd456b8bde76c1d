// `rheodda check`, `rheodda run`, `rheodda plot`: scenes from YAML files.
// Sample runs:
//   rheodda check examples/shear-creep-test.yaml
//   rheodda run examples/shear-creep-test.yaml -o out/shear-creep
//   rheodda plot out/shear-creep
#include <fmt/format.h>

#include <memory>
#include <string>

#include "commands.hpp"
#include "rheodda/scene/describe.hpp"
#include "rheodda/scene/loader.hpp"

namespace rheodda::apps {

void add_scene_commands(CLI::App& app) {
  auto file = std::make_shared<std::string>();
  auto* check = app.add_subcommand(
      "check", "Validate a scene file and print what will be modelled, without running it");
  check->add_option("SCENE", *file, "Scene file (YAML, docs/scene-format.md)")->required();
  check->callback([file] {
    const scene::SceneDescription s = scene::load_scene(*file);
    fmt::print("{}", scene::describe_scene(s));
    fmt::print("scene OK\n");
  });
}

}  // namespace rheodda::apps
