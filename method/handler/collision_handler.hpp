#pragma once
/// The interface of every collision handling method: the paper's
/// interruptible method and every baseline (docs/architecture.md).
///
/// init() receives the collision settings the run resolved once for this
/// world (collision_settings.hpp; their warnings are the run's to record) and
/// is not timed. step() reads the world's current positions and velocities
/// and adds contact forces into Body::contact_force_n; the run loop times it
/// (handling_ms) and then integrates. A method's own settings are handed to
/// its constructor, typed and checked (method_settings.hpp, baselines/registry.cpp).
///
/// Most methods schedule the shared collision cycle differently: derive from
/// CycleHandler (cycle_handler.hpp) rather than from this interface.

#include <cstdint>
#include <optional>
#include <vector>

#include "method/handler/budget.hpp"
#include "method/handler/contact.hpp"
#include "method/handler/collision_settings.hpp"
#include "method/handler/stage_costs.hpp"

namespace tcb {

/// Where a force a point was given this step came from (issue 20's force
/// error splits by it):
///   Computed      a depth computed in this step
///   Held          a depth (or force) computed in an earlier step, applied as it was:
///                 the paper's cycle spanning steps, every_nth holding forces
///   Extrapolated  the paper's estimate from the point's force history
///   Tracked       a depth from an earlier step carried to the current
///                 positions (interruptible_tracked)
enum class ForceSource : std::uint8_t { Computed, Held, Extrapolated, Tracked };
inline constexpr std::size_t kForceSources = 4;

struct ForcePoint {
  std::int32_t object = -1, vertex = -1;
  ForceSource source = ForceSource::Computed;
};

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
  /// Time and work per stage of the collision cycle, and the handler's own
  /// `apply` (stage_costs.hpp); all zero for a method without a cycle.
  StageCosts stages;
  /// Every point given a contact force this step (its own force; the
  /// reactions on tet vertices are not listed), with its source.
  std::vector<ForcePoint> force_points;
};

class CollisionHandler {
 public:
  virtual ~CollisionHandler() = default;
  virtual void init(const World& world, const CollisionSettings& settings) = 0;
  virtual StepReport step(World& world, Budget& budget) = 0;
  /// The colliding points the method holds after the last step.
  virtual const std::vector<Contact>& contacts() const = 0;
  /// Whether contacts() lists colliding points (every method of the paper's
  /// kind). False for a whole-body detector (`neural`): it says only whether
  /// a body collides with itself, so point-level recall and precision do not
  /// apply to it; self_collision_verdicts() is what it reports.
  virtual bool reports_points() const { return true; }
  /// Per body of the world, after the last step: 1 when the method says the
  /// body collides with itself, else 0. The default reads contacts(): some
  /// point of the body inside a tet of the same body.
  virtual std::vector<char> self_collision_verdicts(const World& world) const;
  /// Heap bytes of the method's own data (hash tables, boxes, contacts,
  /// scratch; not the world), for run.json's memory per tet; nullopt where a
  /// method does not count it.
  virtual std::optional<std::size_t> memory_bytes() const { return std::nullopt; }
  /// For methods that run the collision cycle: cycles begun, and how many
  /// fresh tet hashes completed (none for brute force; under keep_table the
  /// other cycles refreshed the last table); nullopt for the others.
  struct CycleCounts {
    std::int64_t begun = 0;
    std::int64_t tet_hashes_fresh = 0;
  };
  virtual std::optional<CycleCounts> cycle_counts() const { return std::nullopt; }
};

}  // namespace tcb
