#pragma once
/// `every_nth`: a full collision cycle every n-th step (seed 000's naive
/// alternative, n = 2 there), and in between either the last cycle's forces
/// again (hold = true, the default) or no collision forces at all
/// (hold = false). Settings: [every_nth] n = 2, hold = true
/// (or --set every_nth.n=2).

#include <memory>

#include "method/handler/collision_cycle.hpp"
#include "method/handler/collision_handler.hpp"

namespace tcb {

class EveryNthHandler final : public CollisionHandler {
 public:
  EveryNthHandler(int n, bool hold_forces) : m_n(n), m_hold(hold_forces) {}
  std::string_view name() const override { return "every_nth"; }
  void init(const World& world, const SceneDesc& scene) override;
  StepReport step(World& world, Budget& budget) override;
  const std::vector<Contact>& contacts() const override;
  std::vector<std::string> warnings() const override { return m_cycle ? m_cycle->settings().warnings : std::vector<std::string>{}; }

 private:
  int m_n;
  bool m_hold;
  std::int64_t m_step = 0;
  std::unique_ptr<CollisionCycle> m_cycle;
};

}  // namespace tcb
