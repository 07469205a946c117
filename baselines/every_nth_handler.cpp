#include "baselines/every_nth_handler.hpp"

namespace tcb {

StepReport EveryNthHandler::schedule_step(World& world, Budget& budget) {
  StepReport report;
  const bool run_cycle = m_step++ % m_n == 0;
  if (run_cycle) {
    report.work_units = run_whole_cycle(world, budget);
    report.cycle_done = true;
  }
  report.cycle = cycle().number();
  if (run_cycle || m_hold) {
    apply_cycle_forces(world, report, run_cycle ? ForceSource::Computed : ForceSource::Held);
    if (!run_cycle) {  // held forces are not computed from this step's depths
      report.estimated_forces = report.exact_forces;
      report.exact_forces = 0;
      report.exact_points.clear();
    }
  } else {
    report.colliding_points = static_cast<std::int64_t>(cycle().contacts().size());
  }
  return report;
}

}  // namespace tcb
