#include "method/handler/interruptible_handler.hpp"

#include "method/response/penalty_response.hpp"

namespace tcb {

void InterruptibleHandler::init(const World& world, const SceneDesc& scene) {
  m_cycle = std::make_unique<CollisionCycle>(world, resolve_collision_settings(world, scene));
  for (const Body& b : world.bodies) {
    m_history.emplace_back(b.x_m.size());
    m_has_history.emplace_back(b.x_m.size(), 0);
    m_applied.emplace_back(b.x_m.size(), 0);
  }
}

StepReport InterruptibleHandler::step(World& world, Budget& budget) {
  ++m_step;
  if (!m_in_progress) {
    m_cycle->begin(world);
    m_cycle_start = m_step;
    m_in_progress = true;
  }
  const std::uint64_t before = budget.spent();
  const bool done = m_cycle->advance(world, budget);
  StepReport report;
  report.work_units = budget.spent() - before;
  report.cycle = m_cycle->number();
  report.cycle_done = done;

  const auto& contacts = m_cycle->contacts();
  const std::size_t with_force = m_cycle->forces_computed();
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const Contact& c = contacts[i];
    m_applied[c.object][c.vertex] = m_step;  // decided here, so the history loop below leaves it alone
    if (c.separated) continue;               // left the object since detection: no force
    if (c.depth_source != DepthSource::None) {
      const Vec3 f = i < with_force ? c.force_n
                                    : penalty_force(world, c, m_cycle->settings().response(c.object, c.other),
                                                    m_cycle->settings().dt_s);
      apply_contact_force(world, c, f);
      ++report.exact_forces;
      report.exact_points.emplace_back(c.object, c.vertex);
    } else if (!done && m_extrapolate && m_has_history[c.object][c.vertex]) {
      apply_contact_force(world, c, extrapolated_force(m_history[c.object][c.vertex], m_step));
      ++report.estimated_forces;
    }
  }
  if (!done && m_extrapolate) {
    // Points in contact in earlier cycles that this cycle has not reached yet.
    for (std::size_t b = 0; b < m_history.size(); ++b)
      for (std::size_t v = 0; v < m_history[b].size(); ++v) {
        if (!m_has_history[b][v] || m_applied[b][v] == m_step) continue;
        ForceHistory& h = m_history[b][v];
        apply_contact_force(world, h.contact, extrapolated_force(h, m_step));
        ++report.estimated_forces;
      }
  }
  if (done) {
    const std::int64_t cycle_steps = m_step - m_cycle_start + 1;
    for (auto& flags : m_has_history) std::fill(flags.begin(), flags.end(), 0);
    for (const Contact& c : contacts) {
      if (c.depth_source == DepthSource::None) continue;
      record_depth_force(m_history[c.object][c.vertex], c, m_step, cycle_steps);
      m_has_history[c.object][c.vertex] = 1;
    }
    // Points this cycle did not find lose their history.
    for (std::size_t b = 0; b < m_history.size(); ++b)
      for (std::size_t v = 0; v < m_history[b].size(); ++v)
        if (!m_has_history[b][v]) m_history[b][v] = ForceHistory{};
    m_completed.clear();
    for (const Contact& c : contacts)
      if (!c.separated) m_completed.push_back(c);
    m_in_progress = false;
  }
  report.colliding_points = static_cast<std::int64_t>(m_completed.size());
  report.depth_fallback = done ? m_cycle->depth_fallback() : 0;
  return report;
}

}  // namespace tcb
