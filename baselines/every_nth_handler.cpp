#include "baselines/every_nth_handler.hpp"

#include "baselines/full_handler.hpp"

namespace tcb {

void EveryNthHandler::init(const World& world, const SceneDesc& scene) {
  m_cycle = std::make_unique<CollisionCycle>(world, resolve_collision_settings(world, scene));
}

StepReport EveryNthHandler::step(World& world, Budget& budget) {
  StepReport report;
  const bool run_cycle = m_step++ % m_n == 0;
  if (run_cycle) {
    Budget unlimited = Budget::unlimited();
    m_cycle->begin(world);
    m_cycle->advance(world, unlimited);
    budget.charge(unlimited.spent());
    report.work_units = unlimited.spent();
    report.cycle_done = true;
  }
  report.cycle = m_cycle->number();
  if (run_cycle || m_hold) {
    apply_cycle_forces(world, *m_cycle, report);
    if (!run_cycle) {  // held forces are not computed from this step's depths
      report.estimated_forces = report.exact_forces;
      report.exact_forces = 0;
      report.exact_points.clear();
    }
  } else {
    report.colliding_points = static_cast<std::int64_t>(m_cycle->contacts().size());
  }
  return report;
}

const std::vector<Contact>& EveryNthHandler::contacts() const { return m_cycle->contacts(); }

}  // namespace tcb
