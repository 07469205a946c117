#pragma once
/// The paper's method: time-critical, interruptible collision
/// handling. `interruptible`, the ablation `interruptible_no_extrapolation`,
/// and our variants `interruptible_tracked` (below) and
/// `interruptible_prioritized` (fastest points first, collision_cycle.hpp).
/// The settings fine_tasks, reserve_apply, apply_first, widen_stale,
/// rehash_stale and predict_tasks (InterruptibleOptions) are ours
/// too; by default every one of them keeps the paper's schedule.
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
/// it no longer finds are forgotten: recorded at the start of the next step,
/// before its first poll (a wall budget sees the time), with the step the
/// cycle completed in (extrapolation counts from there).
///
/// The setting apply_first (ours) applies the step's forces (the rules
/// above) at its start instead, from the cycle as the previous step left it,
/// so applying lies before the first poll too; a depth then acts one step
/// later, and a completed cycle's contacts act alone in the step after it.
///
/// `interruptible_tracked` (a variant, not in the paper) tracks depths instead
/// of extrapolating forces. Every depth keeps the offset r0 = x_point -
/// x_tet(barycentric) of the step in which it was computed (Contact::
/// depth_offset_m), and in any later step it is carried to the current
/// positions, d = d0 - (r - r0) . n (tracked_depth_m); the point gets the
/// penalty force of d with the current velocities, none once d <= 0. This
/// holds both for depths of the current cycle computed in an earlier step of
/// it and, while the cycle has no depth for the point yet, for its last
/// depth-based contact. It removes the delay for contacts that persist; new
/// contacts still wait for their cycle. Tracked forces are depth-based, so
/// under implicit response they are links like any other. Cost: one tet
/// interpolation per such point per step (not charged to the budget, like the
/// extrapolation). With an unlimited budget every depth is used in the step
/// it was computed in (d = d0) and the forces are bit for bit those of `full`.
/// A tracked contact also outlives `keep_lost_cycles` completed cycles that no
/// longer find its point (setting, default 1; 0 forgets it at once, like the
/// paper's history): a plate corner that bounced out of contact while a cycle
/// looked gets its force back the step it re-enters, instead of a whole cycle
/// or two later. On plates20 at full-work/6 this is the difference between a
/// chattering stack (0: settled kinetic energy 0.59 J) and a resting one (1:
/// 0.016 J, full's 0.013 J). Its risk: a point that slid out sideways keeps a
/// force while its tracked depth is > 0, for at most that many cycles. In the
/// step a cycle completes, only that cycle's contacts act (as in `full`;
/// under apply_first, in the step after).
///
/// Under implicit response (collision_settings.hpp) every force above is a
/// link solved with the bodies: depth-based ones with their depth, an
/// extrapolated one with the equivalent depth of its normal part
/// (add_force_link), so the contact's spring and damper are integrated
/// implicitly whatever the force's source.
/// contacts() is the last completed cycle's colliding points.

#include <memory>
#include <optional>

#include "method/handler/cycle_handler.hpp"
#include "method/handler/force_extrapolation.hpp"

namespace tcb {

struct InterruptibleOptions {
  /// Track only: how many completed cycles a tracked contact outlives the
  /// last cycle that found its point with a depth (0 here; the registry's
  /// interruptible_tracked defaults to 1).
  std::int64_t keep_lost_cycles = 0;
  /// The cycle's schedule (collision_cycle.hpp), the paper's by default: its
  /// task granularity (TaskGranularity::fine_tasks() is the setting
  /// fine_tasks), its work order (fastest first: the variant
  /// interruptible_prioritized), widened queries (the setting widen_stale),
  /// rehashed tets (rehash_stale) and predicted stops (predict_tasks).
  CycleSchedule schedule{};
  /// Under a wall budget, stop the cycle early by the time applying the
  /// forces took in recent steps (ours, the setting reserve_apply): the
  /// paper's budget covers the cycle's tasks, and the forces are applied
  /// after the last interruption point. Capped at half the budget, so the
  /// cycle still advances.
  bool reserve_apply = false;
  /// Apply the forces at the start of each step, from the cycle as the last
  /// step left it, and give the cycle what is left of the budget (ours, the
  /// setting apply_first). The paper applies after the cycle's last
  /// interruption point, where no wall budget sees it; here a step overruns
  /// by its last task (and, when it completes a cycle, the copy of its
  /// contacts that contacts() returns). The price: a depth found in a step acts from
  /// the next one (one step more latency), and a completed cycle's forces act
  /// in the step after it completed. reserve_apply has nothing left to do.
  bool apply_first = false;
};

class InterruptibleHandler final : public CycleHandler {
 public:
  /// What a point gets while its cycle has no depth for it yet.
  enum class Stale { Extrapolate, Nothing, Track };
  using Options = InterruptibleOptions;
  explicit InterruptibleHandler(Stale stale, Options options = {});
  void init(const World& world, const CollisionSettings& settings) override;
  StepReport schedule_step(World& world, Budget& budget) override;
  const std::vector<Contact>& contacts() const override { return m_completed; }
  /// The cycle's memory and the force histories, tracked contacts and
  /// per-vertex records this handler keeps between steps.
  std::optional<std::size_t> memory_bytes() const override;

 private:
  /// The stale force of a point (extrapolated, or of its tracked depth) and
  /// the contact whose tet takes its reaction.
  struct StaleForce {
    Contact where;  ///< for a tracked force: the contact with its depth carried to now
    Vec3 force_n;
    bool tracked;
  };
  struct HistoryEntry;
  /// `history`: the point's entry in m_histories, nullptr if it has none.
  std::optional<StaleForce> stale_force(const World& world, std::int32_t object, std::int32_t vertex,
                                        HistoryEntry* history);
  void apply_stale(World& world, const StaleForce& force) const;
  ForceSource stale_source() const { return m_stale == Stale::Track ? ForceSource::Tracked : ForceSource::Extrapolated; }
  /// The history after a cycle that completed at `step` in `cycle_steps` steps.
  void remember_completed_cycle(const std::vector<Contact>& contacts, std::int64_t step, std::int64_t cycle_steps);
  /// The forces of the cycle's current state, per the rules above: of its
  /// contacts, and while it is incomplete, extrapolated (or tracked) ones.
  void apply_forces(World& world, StepReport& report, bool cycle_complete);
  using Point = std::pair<std::int32_t, std::int32_t>;  // (body, vertex)

  Stale m_stale;
  bool m_in_progress = false;
  std::int64_t m_step = 0, m_cycle_start = 0;
  /// A point with a history. The entries are dense, in ascending point
  /// order, so the loop that applies the stale forces of points the cycle has
  /// not reached reads them in one sweep instead of one per-vertex record
  /// (sizeof(ForceHistory): 240 bytes on x86-64) scattered over the body: that loop runs in every
  /// step of a cycle, after the dynamics have evicted the caches.
  struct HistoryEntry {
    Point point;
    bool keep = false;  // remember_completed_cycle(): stays in the history
    ForceHistory history;
  };
  std::vector<HistoryEntry> m_histories;         // ascending by point
  std::vector<HistoryEntry> m_histories_before;  // remember_completed_cycle(): the previous list
  std::vector<HistoryEntry> m_histories_new;     // remember_completed_cycle(): points new to it
  std::vector<std::vector<std::int32_t>> m_history_index;  // per body, per vertex: entry in m_histories, or -1
  std::vector<std::vector<Contact>> m_tracked;        // per body, per vertex (Track only): last depth contact
  std::int64_t m_keep_lost_cycles;
  std::vector<std::vector<std::int64_t>> m_lost_cycles;  // per vertex (kept contacts only): cycles not found since
  std::vector<std::vector<std::int64_t>> m_applied;   // per vertex: last step a force was decided for it
  std::vector<Contact> m_completed;
  bool m_remember_pending = false;          // a cycle completed last step: its history is still to be recorded
  std::int64_t m_remember_cycle_steps = 1;  // that cycle's length in steps
  bool m_reserve_apply;
  bool m_apply_first;
  double m_apply_ms_done = 0.0, m_apply_ms_running = 0.0;  // recent apply times (reserve_apply), per step kind
};

}  // namespace tcb
