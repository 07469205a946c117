#pragma once
/// What collision handling knows about one colliding point (METHOD.md s.1):
/// vertex `vertex` of body `object` lies inside tet `tet` of body `other`
/// (other == object for self-collision), with its penetration depth and
/// direction once known and the penalty force computed from them.
/// Units: depth m (positive inside, unsquared), force N.

#include <array>
#include <cstdint>

#include "sim/mesh/tet_mesh.hpp"

namespace tcb {
class World;
}

namespace tcb {

enum class DepthSource : std::uint8_t {
  None,        ///< not known (yet); no depth-based force
  Border,      ///< from the point's border edges (Heidelberger et al. 2004)
  Propagated,  ///< propagated from neighbours with a depth
  TetPair,     ///< a tet pair's penetration (GJK + EPA; the fcl_tets baseline)
};

struct Contact {
  std::int32_t object = -1, vertex = -1;
  std::int32_t other = -1, tet = -1;
  std::array<double, 4> barycentric{};  ///< of the point in the tet at detection; sums to 1
  DepthSource depth_source = DepthSource::None;
  std::int32_t layer = -1;              ///< propagation layer (0 for border points)
  std::int64_t detected_step = 0;       ///< World::step_index when it was detected
  std::int64_t depth_step = -1;         ///< World::step_index when its depth was computed (-1: none)
  bool separated = false;               ///< re-checked in a later step and found outside: inert
  double depth_m = 0.0;
  Vec3 direction = Vec3::Zero();        ///< unit; pushes the point out of `other`
  /// r0 = x_point - x_tet(barycentric) when the depth was computed (m): a
  /// later step tracks the depth as depth_m - (r - r0) . direction.
  Vec3 depth_offset_m = Vec3::Zero();
  Vec3 force_n = Vec3::Zero();          ///< on the point; the reaction goes to the tet
};

/// x_point - x_tet(barycentric) with the world's current positions (m): zero
/// while the point sits where it was detected in the tet.
Vec3 contact_offset_m(const World& world, const Contact& contact);

/// The contact's depth carried to the current positions: depth_m minus how far
/// the point has moved out along direction, relative to the tet, since the
/// depth was computed (m; <= 0 once it has left along the normal).
double tracked_depth_m(const World& world, const Contact& contact);

}  // namespace tcb
