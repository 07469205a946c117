#include "baselines/full_handler.hpp"

namespace tcb {

StepReport FullHandler::schedule_step(World& world, Budget& budget) {
  StepReport report;
  report.work_units = run_whole_cycle(world, budget);
  report.cycle = cycle().number();
  report.cycle_done = true;
  apply_cycle_forces(world, report);
  return report;
}

}  // namespace tcb
