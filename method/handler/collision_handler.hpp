#pragma once
/// The interface of every collision handling method: the paper's
/// interruptible method and every baseline (ARCHITECTURE.md).
///
/// step() reads the world's current positions and velocities and adds contact
/// forces into Body::contact_force_n; the run loop times it (handling_ms) and
/// then integrates. init() is not timed.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "method/handler/budget.hpp"
#include "method/handler/contact.hpp"
#include "sim/world/scene.hpp"

namespace tcb {

struct StepReport {
  std::uint64_t work_units = 0;
  std::int64_t cycle = 0;          ///< the collision cycle worked on (1-based; 0 none)
  bool cycle_done = false;         ///< a cycle completed in this step
  std::int64_t colliding_points = 0;
  std::int64_t exact_forces = 0;   ///< points given a depth-based force this step
  std::int64_t estimated_forces = 0;  ///< points given an estimated or extrapolated force
  std::int64_t depth_fallback = 0; ///< colliding points that got no depth (no border path)
  /// (body, vertex) of the points given a depth-based force this step (for
  /// the latency metric).
  std::vector<std::pair<std::int32_t, std::int32_t>> exact_points;
};

class CollisionHandler {
 public:
  virtual ~CollisionHandler() = default;
  virtual std::string_view name() const = 0;
  virtual void init(const World& world, const SceneDesc& scene) = 0;
  virtual StepReport step(World& world, Budget& budget) = 0;
  /// The colliding points the method holds after the last step.
  virtual const std::vector<Contact>& contacts() const = 0;
  /// Doubtful settings found by init(), in words; recorded with the run.
  virtual std::vector<std::string> warnings() const { return {}; }
};

}  // namespace tcb
