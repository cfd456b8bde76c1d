// Scene files parsed by libyaml into yaml-cpp nodes (the loader's interface), with
// every node's line and column.
//
// Why: yaml-cpp 0.7's own scanner takes 8 s of the 13 s `rheodda check` spends on
// an explicit rock mass of 93 000 blocks (24 MB, written by `rheodda generate`),
// libyaml's 1 s (docs/guide/rockmass.md, "Performance"). The nodes are the ones yaml-cpp's
// YAML::Load builds (its NodeBuilder, redone here), so the loader reads them as before.
#pragma once

#include <stdexcept>
#include <string>

#include <yaml-cpp/yaml.h>

namespace rheodda::scene {

/// A YAML syntax error: libyaml's problem and where (0-based, as YAML::Mark).
class YamlSyntaxError : public std::runtime_error {
 public:
  YamlSyntaxError(const std::string& problem, int line, int column)
      : std::runtime_error(problem), line_(line), column_(column) {}
  int line() const { return line_; }
  int column() const { return column_; }

 private:
  int line_, column_;
};

/// The first document of UTF-8 `text` as yaml-cpp nodes with their marks: maps,
/// sequences and scalars, plain `~`, `null`, `Null`, `NULL` and empty values as null
/// (as yaml-cpp reads them), anchors and aliases. Nesting deeper than 2000 levels is
/// refused (yaml-cpp's own limit). Throws YamlSyntaxError.
YAML::Node load_yaml_document(const std::string& text);

}  // namespace rheodda::scene
