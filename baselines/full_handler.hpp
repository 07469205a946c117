#pragma once
/// `full`: the whole collision cycle every step, never interrupted (the
/// paper's reference "without time constraint"). A budget passed to step() is
/// only charged with the work done, never obeyed. With DetectionMode::BruteForce
/// the same handler is `brute_force`: every point against every tet, the O(n^2)
/// reference the cross-method tests compare with.

#include "method/handler/cycle_handler.hpp"

namespace tcb {

class FullHandler final : public CycleHandler {
 public:
  using CycleHandler::CycleHandler;
  StepReport schedule_step(World& world, Budget& budget) override;
};

}  // namespace tcb
