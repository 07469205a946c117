#pragma once
/// The paper's method (seed 000): time-critical, interruptible collision
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
/// it no longer finds are forgotten. With an unlimited budget every cycle
/// completes within its step and the forces are bit for bit those of `full`.
/// contacts() is the last completed cycle's colliding points.

#include <memory>

#include "method/handler/collision_cycle.hpp"
#include "method/handler/collision_handler.hpp"
#include "method/handler/force_extrapolation.hpp"

namespace tcb {

class InterruptibleHandler final : public CollisionHandler {
 public:
  explicit InterruptibleHandler(bool extrapolate) : m_extrapolate(extrapolate) {}
  std::string_view name() const override {
    return m_extrapolate ? "interruptible" : "interruptible_no_extrapolation";
  }
  void init(const World& world, const SceneDesc& scene) override;
  StepReport step(World& world, Budget& budget) override;
  const std::vector<Contact>& contacts() const override { return m_completed; }
  std::vector<std::string> warnings() const override { return m_cycle->settings().warnings; }
  const CollisionCycle& cycle() const { return *m_cycle; }

 private:
  bool m_extrapolate;
  std::unique_ptr<CollisionCycle> m_cycle;
  bool m_in_progress = false;
  std::int64_t m_step = 0, m_cycle_start = 0;
  std::vector<std::vector<ForceHistory>> m_history;   // per body, per vertex
  std::vector<std::vector<char>> m_has_history;
  std::vector<std::vector<std::int64_t>> m_applied;   // per vertex: last step a force was decided for it
  std::vector<Contact> m_completed;
};

}  // namespace tcb
