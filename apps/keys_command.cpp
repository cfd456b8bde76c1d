// `rheodda keys`: the declared scene keys (scene/include/rheodda/scene/keys.hpp)
// with their units, meanings and defaults; `--markdown` prints the key tables that
// docs/reference/scene-format.md holds (scripts/scene-format-tables.sh splices them in);
// `rheodda keys settings` the engine's declared settings (core/settings.hpp), whose
// table docs/reference/engine.md holds.
#include <fmt/format.h>

#include <algorithm>
#include <iostream>
#include <set>

#include "commands.hpp"
#include "rheodda/core/settings.hpp"
#include "rheodda/scene/history_columns.hpp"
#include "rheodda/scene/keys.hpp"

namespace rheodda::apps {

void add_keys_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("keys", "Print the declared scene keys (analysis, materials, joint_sets, blocks, "
                                         "rock_mass, the points, water, bolts, ...) with unit, default and meaning");
  auto map = std::make_shared<std::string>();
  auto markdown = std::make_shared<bool>(false);
  cmd->add_option("map", *map, "Only this map, as `rheodda keys` names it: analysis, analysis.settle, materials, ...; "
                               "`settings`: the engine's settings (docs/reference/engine.md); `history`: history.csv's columns "
                               "(docs/reference/outputs.md)");
  cmd->add_flag("--markdown", *markdown, "Print Markdown tables, as docs/reference/scene-format.md (and engine.md) hold them");
  cmd->callback([map, markdown] {
    if (*map == "history") {  // history.csv's columns (scene/history_columns.hpp): docs/reference/outputs.md's table
      if (*markdown) {
        std::cout << scene::history_table_markdown();
        return;
      }
      for (const scene::HistoryColumns& c : scene::history_column_specs())
        for (const std::string& n : c.names) std::cout << fmt::format("history.{} [{}]: {}\n", n, c.unit, c.meaning);
      return;
    }
    if (*map == "settings") {  // the engine's settings (core/settings.hpp): docs/reference/engine.md's table
      if (*markdown) {
        std::cout << core::settings_table_markdown();
        return;
      }
      for (const core::SettingSpec& s : core::setting_specs())
        std::cout << fmt::format("settings.{} [{}] {} default {}: {}\n", s.name(), s.parameter.unit, s.range_text(),
                                 s.default_text(), s.parameter.meaning);
      return;
    }
    std::vector<std::string> maps;
    for (const auto& m : scene::declared_maps()) maps.push_back(m.name);
    if (!map->empty()) {
      if (std::find(maps.begin(), maps.end(), *map) == maps.end())
        throw CLI::ValidationError("map", fmt::format("'{}' has no declared keys; declared maps: {}, settings", *map,
                                                      fmt::join(maps, ", ")) + ", history");
      maps = {*map};
    }
    for (const auto& m : maps) {
      if (*markdown) {
        std::cout << scene::key_table_markdown(m);
        continue;
      }
      for (const auto& k : scene::declared_keys(m))
        std::cout << fmt::format("{}.{} [{}]{} default {}: {}\n", m, k.name, k.unit,
                                 scene::key_range_text(k).empty() ? "" : " " + scene::key_range_text(k), k.default_text,
                                 k.meaning);
    }
  });
}

}  // namespace rheodda::apps
