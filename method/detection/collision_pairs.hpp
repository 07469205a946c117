#pragma once
/// Which bodies are tested against which (METHOD.md s.2; only what a scene
/// requires is modelled): every pair of distinct bodies except two passive
/// ones (nothing they do moves anything), and a body against itself only when
/// it enables self_collision. Symmetric.

#include <vector>

#include "sim/world/world.hpp"

namespace tcb {

class CollisionPairs {
 public:
  explicit CollisionPairs(const World& world);
  bool enabled(std::size_t a, std::size_t b) const { return m_enabled[a * m_count + b] != 0; }
  /// Whether body b's tets are tested against any body's points.
  bool has_partner(std::size_t b) const { return m_has_partner[b] != 0; }
  std::size_t body_count() const { return m_count; }

 private:
  std::size_t m_count;
  std::vector<char> m_enabled, m_has_partner;
};

/// Barycentric coordinates of p in tet (v0..v3), in floating point, clamped to
/// [0, 1] and renormalised to sum to 1 (a point on a face gets a 0 weight).
std::array<double, 4> barycentric_weights(const Vec3& p, const Vec3& v0, const Vec3& v1, const Vec3& v2, const Vec3& v3);

}  // namespace tcb
