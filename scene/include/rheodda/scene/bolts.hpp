// `bolts:` of a scene file (docs/reference/bolts.md, docs/reference/scene-format.md): rock bolts
// joining a point of one block to a point of another block, or to a fixed
// point in space. Included by scene.hpp after the types it uses (BlockPoint,
// LawChoice); include scene.hpp, not this.
#pragma once

#include <optional>
#include <string>

#include "rheodda/core/bolt.hpp"

namespace rheodda::scene {

/// One bolt (core/include/rheodda/core/bolt.hpp is what it builds into): its properties
/// are the engine's BoltProperties (axial_stiffness, pretension, yield_force,
/// rupture_elongation), declared in core/property_specs.hpp (the keys of the same names;
/// build_bolt hands them on whole); infinite yield_force and rupture_elongation (their
/// defaults): never yields, never ruptures.
struct BoltDescription : core::BoltProperties {
  std::string name;  ///< `name:`, unique among the bolts (bolts.csv's `bolt` column)
  BlockPoint from;   ///< `from: {point, block}`: the first end, on a block
  /// `to: {point, block}` (on a block) or `to: {fixed: [x, y]}` (fixed in space;
  /// then to_fixed is true and to.block is -1).
  BlockPoint to;
  bool to_fixed = false;
  std::optional<LawChoice> law;              ///< `law:` creep of the axial force; unset: none
  SourceLocation where{};
};

}  // namespace rheodda::scene
