// Hand-made blocks for contact-level tests: owns the vertex arrays a BlockView points to.
#pragma once

#include <cmath>
#include <deque>
#include <vector>

#include "rheodda/contact/kinematics.hpp"

namespace rheodda::contact::testing {

struct TestBlock {
  std::vector<Vec2> vertices;  // counter-clockwise [m]
  std::vector<int> edge_joint_set;
  Vec2 centroid = Vec2::Zero();
};

/// Area centroid of a simple polygon.
inline Vec2 polygon_centroid(const std::vector<Vec2>& v) {
  double a = 0.0;
  Vec2 c = Vec2::Zero();
  for (size_t k = 0; k < v.size(); ++k) {
    const Vec2& p = v[k];
    const Vec2& q = v[(k + 1) % v.size()];
    const double w = p.x() * q.y() - q.x() * p.y();
    a += w;
    c += w * (p + q);
  }
  return c / (3.0 * a);
}

/// A scene whose views stay valid while blocks are added (deque storage).
class Scene {
 public:
  int add(std::vector<Vec2> vertices) {
    TestBlock b;
    b.centroid = polygon_centroid(vertices);
    b.vertices = std::move(vertices);
    blocks_.push_back(std::move(b));
    rebuild();
    return static_cast<int>(blocks_.size()) - 1;
  }
  int add_rect(double x0, double y0, double x1, double y1) {
    return add({{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}});
  }
  /// Rigid translation of block b by d [m].
  void translate(int b, const Vec2& d) {
    for (Vec2& v : blocks_[b].vertices) v += d;
    blocks_[b].centroid += d;
    rebuild();
  }
  /// Rigid rotation of block b by theta [rad] (counter-clockwise) about `pivot` [m].
  void rotate(int b, const Vec2& pivot, double theta) {
    const Eigen::Rotation2Dd r(theta);
    for (Vec2& v : blocks_[b].vertices) v = pivot + r * (v - pivot);
    blocks_[b].centroid = pivot + r * (blocks_[b].centroid - pivot);
    rebuild();
  }
  TestBlock& block(int b) { return blocks_[b]; }
  void rebuild() {
    views_.clear();
    for (const TestBlock& b : blocks_)
      views_.push_back({b.vertices, b.centroid, b.edge_joint_set});
  }
  std::span<const BlockView> views() const { return views_; }

 private:
  std::deque<TestBlock> blocks_;
  std::vector<BlockView> views_;
};

/// Square of side s centred at c, rotated by theta [rad], counter-clockwise.
inline std::vector<Vec2> rotated_square(const Vec2& c, double s, double theta) {
  std::vector<Vec2> v;
  for (int k = 0; k < 4; ++k) {
    const double a = theta + (k * 0.5 - 0.75) * 3.14159265358979323846;  // first vertex lowest-left
    v.push_back(c + (s / std::sqrt(2.0)) * Vec2(std::cos(a), std::sin(a)));
  }
  return v;
}

}  // namespace rheodda::contact::testing
