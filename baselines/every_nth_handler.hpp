#pragma once
/// `every_nth`: a full collision cycle every n-th step (the paper's naive
/// alternative, n = 2 there), and in between either the last cycle's forces
/// again (hold = true, the default) or no collision forces at all
/// (hold = false). Settings: [method.every_nth] n = 2, hold = true
/// (or --set method.every_nth.n=2). Under implicit response what is held is
/// the last cycle's contacts as links (their depths as computed then, the
/// damper with the current velocities); under explicit response, their forces.

#include "method/handler/cycle_handler.hpp"

namespace tcb {

class EveryNthHandler final : public CycleHandler {
 public:
  EveryNthHandler(std::int64_t n, bool hold_forces) : m_n(n), m_hold(hold_forces) {}
  StepReport schedule_step(World& world, Budget& budget) override;

 private:
  std::int64_t m_n;
  bool m_hold;
  std::int64_t m_step = 0;
};

}  // namespace tcb
