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
  explicit CycleHandler(DetectionMode mode = DetectionMode::SpatialHash) : m_mode(mode) {}
  void init(const World& world, const CollisionSettings& settings) override;
  const std::vector<Contact>& contacts() const override;
  /// The cycle (after init()), for schedules and tests.
  const CollisionCycle& cycle() const { return *m_cycle; }

 protected:
  /// Starts a new cycle and runs it to the end with an unlimited budget; its
  /// work is charged to `budget` (and returned), which is never obeyed.
  std::uint64_t run_whole_cycle(World& world, Budget& budget);
  /// Applies every depth-based force of the cycle's contacts to the world and
  /// fills the report's counts (exact_forces, exact_points, colliding_points,
  /// depth_fallback).
  void apply_cycle_forces(World& world, StepReport& report) const;

  CollisionCycle& mutable_cycle() { return *m_cycle; }

 private:
  DetectionMode m_mode;
  std::unique_ptr<CollisionCycle> m_cycle;
};

}  // namespace tcb
