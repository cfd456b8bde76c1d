// `rheodda keys`: the declared scene keys (scene/include/rheodda/scene/keys.hpp)
// with their units, meanings and defaults; `--markdown` prints the key tables that
// docs/reference/scene-format.md holds (scripts/scene-format-tables.sh splices them in).
#include <fmt/format.h>

#include <algorithm>
#include <iostream>
#include <set>

#include "commands.hpp"
#include "rheodda/scene/keys.hpp"

namespace rheodda::apps {

void add_keys_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("keys", "Print the declared scene keys (analysis, materials, joint_sets, blocks, "
                                         "rock_mass, the points, water, bolts, ...) with unit, default and meaning");
  auto map = std::make_shared<std::string>();
  auto markdown = std::make_shared<bool>(false);
  cmd->add_option("map", *map, "Only this map, as `rheodda keys` names it: analysis, analysis.settle, materials, ...");
  cmd->add_flag("--markdown", *markdown, "Print Markdown tables, as docs/reference/scene-format.md holds them");
  cmd->callback([map, markdown] {
    std::vector<std::string> maps;
    for (const auto& m : scene::declared_maps()) maps.push_back(m.name);
    if (!map->empty()) {
      if (std::find(maps.begin(), maps.end(), *map) == maps.end())
        throw CLI::ValidationError("map", fmt::format("'{}' has no declared keys; declared maps: {}", *map,
                                                      fmt::join(maps, ", ")));
      maps = {*map};
    }
    for (const auto& m : maps) {
      if (*markdown) {
        std::cout << scene::key_table_markdown(m);
        continue;
      }
      for (const auto& k : scene::declared_keys(m))
        std::cout << fmt::format("{}.{} [{}] default {}: {}\n", m, k.name, k.unit, k.default_text, k.meaning);
    }
  });
}

}  // namespace rheodda::apps
