// Validation of a model's bolts (bolt.hpp; docs/reference/bolts.md): every refusal names
// the entry "bolts[k].key" (ModelError::key) so a scene reader can point at
// its file and line.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>

#include "engine_impl.hpp"
#include "bolts.hpp"
#include "rheodda/core/property_specs.hpp"

namespace rheodda::core {

namespace {

/// Is p inside the polygon or within tol of its boundary? (As the checks of
/// the other block points, model_checks.cpp.)
bool on_block(const std::vector<Vec2>& v, const Vec2& p) {
  Eigen::AlignedBox2d box;
  for (const auto& q : v) box.extend(q);
  return inside_or_near(v, p, 1e-9 * box.diagonal().norm());  // engine_impl.hpp
}

}  // namespace

void validate_bolt_values(const Bolt& b, const ModelEntry& key) {
  if (b.block_a == b.block_b) throw ModelError(key, "block_b", "a bolt joins two blocks, not a block to itself");
  if (!((b.point_b - b.point_a).norm() > 0.0) || !(b.installed_length >= 0.0))
    throw ModelError(key, "point_b", "the two ends coincide: a bolt needs a length");
  check_declared(bolt_specs(), static_cast<const BoltProperties&>(b), key);  // property_specs.hpp
  if (std::abs(b.pretension) > b.yield_force)
    throw ModelError(key, "pretension", "must be within the yield force (force)");
  if (b.pretension / b.axial_stiffness >= b.rupture_elongation)
    throw ModelError(key, "pretension", "stretches the bolt beyond its rupture elongation when installed");
  if (b.law) {
    if (const auto e1 = b.law->instantaneous_stiffness();
        e1 && std::abs(*e1 - b.axial_stiffness) > 1e-12 * b.axial_stiffness)
      throw ModelError(key, "law", "the law's instantaneous stiffness E1 (" + std::to_string(*e1) +
                                         ") is the bolt's spring and must equal axial_stiffness (" +
                                         std::to_string(b.axial_stiffness) + ")");
    if (b.law->failure_time(1.0))
      throw ModelError(key, "law", "a damage law's failure is not modelled on a bolt; use rupture_elongation");
  }
}

void validate_bolt_settings(const Settings& s) {
  if (s.contact_solver == ContactSolver::newton)
    throw ModelError("settings.contact_solver",
                     "the newton contact solve's residual does not hold the bolts' forces; use open_close "
                     "(docs/reference/bolts.md, \"Limits\")");
}

void validate_bolts(const Model& m) {
  const int blocks = static_cast<int>(m.blocks.size());
  for (std::size_t k = 0; k < m.bolts.size(); ++k) {
    const Bolt& b = m.bolts[k];
    const ModelEntry key{"bolts", k};
    auto end = [&](const char* which, int block, const Vec2& p, bool may_be_fixed) {
      const ModelEntry at = key.within(which);
      if (!(std::isfinite(p.x()) && std::isfinite(p.y()))) throw ModelError(at, "point", "must be finite");
      if (block < 0 && may_be_fixed) return;
      if (block < 0 || block >= blocks) throw ModelError(at, "block", "no block with index " + std::to_string(block));
      if (!on_block(m.blocks[block].vertices, p))
        throw ModelError(at, "point", "lies outside block " + std::to_string(block));
    };
    end("a", b.block_a, b.point_a, false);
    end("b", b.block_b, b.point_b, true);
    validate_bolt_values(b, key);
  }
  if (!m.bolts.empty()) validate_bolt_settings(m.settings);
}

}  // namespace rheodda::core
