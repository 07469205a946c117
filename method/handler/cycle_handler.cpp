#include "method/handler/cycle_handler.hpp"

#include "method/response/penalty_response.hpp"

namespace tcb {

void CycleHandler::init(const World& world, const CollisionSettings& settings) {
  m_cycle = std::make_unique<CollisionCycle>(world, settings, m_mode, m_schedule);
}

StepReport CycleHandler::step(World& world, Budget& budget) {
  m_cycle->start_step_costs();
  const double start_ms = m_cycle->clock()();
  StepReport report = schedule_step(world, budget);
  const double end_ms = m_cycle->clock()();
  report.stages = m_cycle->step_costs();
  report.stages.ms_of(CostStage::Apply) = (end_ms - start_ms) - report.stages.total_ms();
  return report;
}

const std::vector<Contact>& CycleHandler::contacts() const {
  static const std::vector<Contact> kNone;  // before init()
  return m_cycle ? m_cycle->contacts() : kNone;
}

std::uint64_t CycleHandler::run_whole_cycle(World& world, Budget& budget) {
  Budget unlimited = Budget::unlimited();
  m_cycle->begin(world);
  m_cycle->advance(world, unlimited);
  budget.charge(unlimited.spent());
  return unlimited.spent();
}

void CycleHandler::apply_cycle_forces(World& world, StepReport& report, ForceSource source) const {
  for (const Contact& c : m_cycle->contacts()) {
    if (c.depth_source == DepthSource::None) continue;
    apply_depth_contact(world, c, c.force_n);
    ++report.exact_forces;
    report.exact_points.emplace_back(c.object, c.vertex);
    report.force_points.push_back({c.object, c.vertex, source});
  }
  report.colliding_points = static_cast<std::int64_t>(m_cycle->contacts().size());
  report.depth_fallback = m_cycle->depth_fallback();
}

void CycleHandler::apply_depth_contact(World& world, const Contact& c) const {
  const CollisionSettings& s = m_cycle->settings();
  if (s.response_mode == ResponseMode::Explicit) {
    apply_contact_force(world, c, penalty_force(world, c, s.response(c.object, c.other), s.dt_s));
  } else {
    add_contact_link(world, c, s.response(c.object, c.other), s.dt_s);
  }
}

void CycleHandler::apply_depth_contact(World& world, const Contact& c, const Vec3& explicit_force_n) const {
  const CollisionSettings& s = m_cycle->settings();
  if (s.response_mode == ResponseMode::Explicit) apply_contact_force(world, c, explicit_force_n);
  else add_contact_link(world, c, s.response(c.object, c.other), s.dt_s);
}

}  // namespace tcb
