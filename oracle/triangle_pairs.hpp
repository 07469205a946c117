#pragma once
/// Intersecting surface triangle pairs between objects, from FCL
/// (BVHModel<AABBd> per body surface, refitted bottom-up each update; the
/// RSS/OBBRSS refit is broken in FCL 0.7, LIBRARIES.md). Part of the oracle.
///
/// Contract: a pair (triangle of A, triangle of B) is listed when FCL's
/// triangle-triangle test reports the two closed triangles as intersecting
/// (FCL's own floating-point test, not an exact predicate; the test suite
/// compares its count with CGAL's exact do_intersect on generic
/// configurations). Only surfaces are seen: a body wholly inside another has
/// no intersecting pairs (the inside oracle finds it). Pairs follow the
/// scene's rule (distinct bodies, not both passive); self-intersection is not
/// listed. Triangles are indices into Body::mesh->surface.

#include <cstdint>
#include <memory>
#include <vector>

#include "sim/world/world.hpp"

namespace tcb {

struct TrianglePair {
  std::int32_t a = -1, b = -1;                  ///< bodies, a < b
  std::int32_t triangle_a = -1, triangle_b = -1;  ///< surface triangle indices
};

class SurfaceTrianglePairs {
 public:
  /// Builds one BVH per body that takes part in a pair (not timed by the run).
  explicit SurfaceTrianglePairs(const World& world);
  ~SurfaceTrianglePairs();
  SurfaceTrianglePairs(const SurfaceTrianglePairs&) = delete;
  SurfaceTrianglePairs& operator=(const SurfaceTrianglePairs&) = delete;

  /// Refits the BVHs to the world's current positions and lists the pairs,
  /// sorted. The world must have the bodies and meshes it was built with.
  std::vector<TrianglePair> find(const World& world);

 private:
  struct Models;
  std::unique_ptr<Models> models_;
};

}  // namespace tcb
