// SceneError: the one exception for bad scene input. It carries the file, the
// 1-based line and column (from yaml-cpp's Node::Mark()) and the dotted key path
// (e.g. "joint_sets.bedding.law.eta1"), so a user can go straight to the fault.
// The `rheodda` command turns it into exit code 2.
#pragma once

#include <stdexcept>
#include <string>

namespace rheodda::scene {

/// Where a value sits in the scene file; line and column are 1-based, 0 when unknown.
struct SourceLocation {
  int line = 0;
  int column = 0;
};

class SceneError : public std::runtime_error {
 public:
  SceneError(std::string file, SourceLocation where, std::string key, std::string message);

  const std::string& file() const { return file_; }
  int line() const { return where_.line; }
  int column() const { return where_.column; }
  /// Dotted path of the offending key, e.g. "analysis.dt" or "blocks[3].polygon".
  const std::string& key() const { return key_; }
  /// The message without the "file:line:column: key:" prefix.
  const std::string& message() const { return message_; }

 private:
  std::string file_;
  SourceLocation where_;
  std::string key_;
  std::string message_;
};

}  // namespace rheodda::scene
