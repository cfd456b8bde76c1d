// `bolts:` of a scene file (docs/reference/bolts.md, docs/reference/scene-format.md): rock bolts
// joining a point of one block to a point of another block, or to a fixed
// point in space. Included by scene.hpp after the types it uses (BlockPoint,
// LawChoice); include scene.hpp, not this.
#pragma once

#include <optional>
#include <string>

namespace rheodda::scene {

/// One bolt (core/include/rheodda/core/bolt.hpp is what it builds into).
struct BoltDescription {
  std::string name;  ///< `name:`, unique among the bolts (bolts.csv's `bolt` column)
  BlockPoint from;   ///< `from: {point, block}`: the first end, on a block
  /// `to: {point, block}` (on a block) or `to: {fixed: [x, y]}` (fixed in space;
  /// then to_fixed is true and to.block is -1).
  BlockPoint to;
  bool to_fixed = false;
  /// `axial_stiffness:` axial force per unit elongation [force/length], > 0;
  /// may be left out when the law has an instantaneous stiffness E1 (then E1).
  double axial_stiffness = 0.0;
  double pretension = 0.0;  ///< `pretension:` axial force at t = 0 [force], tension > 0
  std::optional<double> yield_force;         ///< `yield_force:` [force], > 0; unset: never yields
  std::optional<double> rupture_elongation;  ///< `rupture_elongation:` [length], > 0; unset: never ruptures
  std::optional<LawChoice> law;              ///< `law:` creep of the axial force; unset: none
  SourceLocation where{};
};

}  // namespace rheodda::scene
