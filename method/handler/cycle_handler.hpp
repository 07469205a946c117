#pragma once
/// The common base of the methods that schedule the shared collision cycle
/// (collision_cycle.hpp): it builds the cycle in init(), reports the cycle's
/// colliding points as contacts(), and offers the two things every such
/// schedule needs: running a whole cycle at once (work charged to the step's
/// budget, never obeyed) and applying a finished cycle's forces. A new
/// schedule derives from it and writes only schedule_step(); step() wraps it
/// to record the step's stage costs (stage_costs.hpp: the cycle's stages,
/// and `apply`, the rest of the schedule's time).

#include <memory>

#include "method/handler/collision_cycle.hpp"
#include "method/handler/collision_handler.hpp"

namespace tcb {

class CycleHandler : public CollisionHandler {
 public:
  explicit CycleHandler(DetectionMode mode = DetectionMode::SpatialHash, CycleSchedule schedule = {})
      : m_mode(mode), m_schedule(schedule) {}
  void init(const World& world, const CollisionSettings& settings) override;
  StepReport step(World& world, Budget& budget) final;
  const std::vector<Contact>& contacts() const override;
  std::optional<std::size_t> memory_bytes() const override { return m_cycle->memory_bytes(); }
  std::optional<CycleCounts> cycle_counts() const override {
    return CycleCounts{m_cycle->number(), m_cycle->fresh_tet_hashes()};
  }
  /// The clock the stage costs are read on (tests inject a ticking one);
  /// after init().
  void set_clock(ClockMs clock) { m_cycle->set_clock(std::move(clock)); }
  /// The cycle (after init()), for schedules and tests.
  const CollisionCycle& cycle() const { return *m_cycle; }

 protected:
  /// One step of the schedule: what step() would be without the cost record.
  virtual StepReport schedule_step(World& world, Budget& budget) = 0;
  /// Starts a new cycle and runs it to the end with an unlimited budget; its
  /// work is charged to `budget` (and returned), which is never obeyed.
  std::uint64_t run_whole_cycle(World& world, Budget& budget);
  /// Applies every depth-based contact of the cycle to the world (its stored
  /// force under explicit response, its link under implicit response) and
  /// fills the report's counts (exact_forces, exact_points, colliding_points,
  /// depth_fallback), each point's force with `source` (force_points).
  void apply_cycle_forces(World& world, StepReport& report, ForceSource source = ForceSource::Computed) const;
  /// One depth-based contact, as the response mode wants it: `explicit_force_n`
  /// under explicit response; under implicit response a link of the contact's
  /// depth (and its friction as a force).
  void apply_depth_contact(World& world, const Contact& contact, const Vec3& explicit_force_n) const;
  /// The same with the contact's penalty force computed now, and only where
  /// it is used (explicit response; the implicit link needs only the depth).
  void apply_depth_contact(World& world, const Contact& contact) const;

  CollisionCycle& mutable_cycle() { return *m_cycle; }

 private:
  DetectionMode m_mode;
  CycleSchedule m_schedule;
  std::unique_ptr<CollisionCycle> m_cycle;
};

}  // namespace tcb
