#pragma once
/// `full`: the whole collision cycle every step, never interrupted (seed
/// 000's reference "without time constraint"). A budget passed to step() is
/// only charged with the work done, never obeyed. With DetectionMode::BruteForce
/// the same handler is `brute_force`: every point against every tet, the O(n^2)
/// reference the cross-method tests compare with.

#include <memory>

#include "method/handler/collision_cycle.hpp"
#include "method/handler/collision_handler.hpp"

namespace tcb {

class FullHandler final : public CollisionHandler {
 public:
  explicit FullHandler(DetectionMode mode = DetectionMode::SpatialHash) : m_mode(mode) {}
  std::string_view name() const override { return m_mode == DetectionMode::SpatialHash ? "full" : "brute_force"; }
  void init(const World& world, const SceneDesc& scene) override;
  StepReport step(World& world, Budget& budget) override;
  const std::vector<Contact>& contacts() const override;
  std::vector<std::string> warnings() const override { return m_cycle ? m_cycle->settings().warnings : std::vector<std::string>{}; }

 private:
  DetectionMode m_mode;
  std::unique_ptr<CollisionCycle> m_cycle;
};

/// Applies every contact's stored force to the world and fills the report's
/// counts; shared by the handlers that apply whole cycles.
void apply_cycle_forces(World& world, const CollisionCycle& cycle, StepReport& report);

}  // namespace tcb
