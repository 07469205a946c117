#include "baselines/full_handler.hpp"

#include "method/response/penalty_response.hpp"

namespace tcb {

void apply_cycle_forces(World& world, const CollisionCycle& cycle, StepReport& report) {
  for (const Contact& c : cycle.contacts()) {
    if (c.depth_source == DepthSource::None) continue;
    apply_contact_force(world, c, c.force_n);
    ++report.exact_forces;
    report.exact_points.emplace_back(c.object, c.vertex);
  }
  report.colliding_points = static_cast<std::int64_t>(cycle.contacts().size());
  report.depth_fallback = cycle.depth_fallback();
}

void FullHandler::init(const World& world, const SceneDesc& scene) {
  m_cycle = std::make_unique<CollisionCycle>(world, resolve_collision_settings(world, scene), m_mode);
}

StepReport FullHandler::step(World& world, Budget& budget) {
  Budget unlimited = Budget::unlimited();
  m_cycle->begin(world);
  m_cycle->advance(world, unlimited);
  budget.charge(unlimited.spent());
  StepReport report;
  report.work_units = unlimited.spent();
  report.cycle = m_cycle->number();
  report.cycle_done = true;
  apply_cycle_forces(world, *m_cycle, report);
  return report;
}

const std::vector<Contact>& FullHandler::contacts() const {
  static const std::vector<Contact> kNone;
  return m_cycle ? m_cycle->contacts() : kNone;
}

}  // namespace tcb
