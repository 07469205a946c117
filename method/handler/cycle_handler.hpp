#pragma once
/// The common base of the methods that schedule the shared collision cycle
/// (collision_cycle.hpp): it builds the cycle in init(), reports the cycle's
/// colliding points as contacts(), and offers the two things every such
/// schedule needs: running a whole cycle at once (work charged to the step's
/// budget, never obeyed) and applying a finished cycle's forces. A new
/// schedule derives from it and writes only step().

#include <memory>

#include "method/handler/collision_cycle.hpp"
#include "method/handler/collision_handler.hpp"

namespace tcb {

class CycleHandler : public CollisionHandler {
 public:
  explicit CycleHandler(DetectionMode mode = DetectionMode::SpatialHash, CycleSchedule schedule = {})
      : m_mode(mode), m_schedule(schedule) {}
  void init(const World& world, const CollisionSettings& settings) override;
  const std::vector<Contact>& contacts() const override;
  /// The cycle (after init()), for schedules and tests.
  const CollisionCycle& cycle() const { return *m_cycle; }

 protected:
  /// Starts a new cycle and runs it to the end with an unlimited budget; its
  /// work is charged to `budget` (and returned), which is never obeyed.
  std::uint64_t run_whole_cycle(World& world, Budget& budget);
  /// Applies every depth-based contact of the cycle to the world (its stored
  /// force under explicit response, its link under implicit response) and
  /// fills the report's counts (exact_forces, exact_points, colliding_points,
  /// depth_fallback).
  void apply_cycle_forces(World& world, StepReport& report) const;
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
