#pragma once
/// The paper's method: time-critical, interruptible collision
/// handling. `interruptible`, and the ablation `interruptible_no_extrapolation`.
///
/// Every step works on the current collision cycle until the step's budget
/// expires (polled only at the cycle's interruption points, collision_cycle.hpp)
/// and resumes it in the next step with the then current positions; a new cycle
/// starts only when the previous one finished, so a cycle may span several
/// steps. Forces applied in a step, per colliding point:
///   - its depth is known in the current cycle: the depth-based force
///     (computed at once with the current velocities if the cycle has not
///     reached its force stage yet) -- counted in exact_forces;
///   - otherwise, while the cycle is incomplete, if the point has depth-based
///     forces from earlier cycles: the extrapolated force
///     (force_extrapolation.hpp), whether or not detection has reached it yet
///     -- counted in estimated_forces; the ablation applies nothing here;
///   - otherwise (a newly colliding point): nothing until its depth is known.
/// When a cycle completes, its depth-based forces enter the history and points
/// it no longer finds are forgotten.
///
/// `interruptible_tracked` (a variant, not in the paper) replaces the force
/// extrapolation: a point with a depth-based force from an earlier step keeps
/// that contact (tet, barycentric position, direction n, depth d0) and the
/// offset r0 = x_point - x_tet(barycentric) of the step the force was applied.
/// In a later step whose cycle has no depth for it yet, its depth is tracked
/// with the current positions, d = d0 - (r - r0) . n, and it gets the penalty
/// force of that depth with the current velocities (none once d <= 0). This
/// removes the delay for contacts that persist; new contacts still wait for
/// their cycle. Cost: one tet interpolation per such point per step (not
/// charged to the budget, like the extrapolation). With an unlimited budget every cycle
/// completes within its step and the forces are bit for bit those of `full`.
/// contacts() is the last completed cycle's colliding points.

#include <memory>
#include <optional>

#include "method/handler/cycle_handler.hpp"
#include "method/handler/force_extrapolation.hpp"

namespace tcb {

class InterruptibleHandler final : public CycleHandler {
 public:
  /// What a point gets while its cycle has no depth for it yet.
  enum class Stale { Extrapolate, Nothing, Track };
  explicit InterruptibleHandler(Stale stale) : m_stale(stale) {}
  void init(const World& world, const CollisionSettings& settings) override;
  StepReport step(World& world, Budget& budget) override;
  const std::vector<Contact>& contacts() const override { return m_completed; }

 private:
  struct Tracked {
    Contact contact;  ///< the last depth-based contact: tet, barycentric, direction, depth d0
    Vec3 offset_m = Vec3::Zero();  ///< r0 = x_point - x_tet(barycentric) when its force was applied
  };
  /// The stale force of a point (extrapolated, tracked, or none) and the
  /// contact whose tet takes its reaction.
  struct StaleForce {
    const Contact* where;
    Vec3 force_n;
  };
  std::optional<StaleForce> stale_force(const World& world, std::int32_t object, std::int32_t vertex);

  Stale m_stale;
  bool m_in_progress = false;
  std::int64_t m_step = 0, m_cycle_start = 0;
  std::vector<std::vector<ForceHistory>> m_history;   // per body, per vertex
  std::vector<std::vector<char>> m_has_history;
  std::vector<std::vector<Tracked>> m_tracked;        // per body, per vertex (Track only)
  std::vector<std::vector<std::int64_t>> m_applied;   // per vertex: last step a force was decided for it
  std::vector<Contact> m_completed;
};

}  // namespace tcb
