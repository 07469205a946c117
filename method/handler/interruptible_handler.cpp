#include "method/handler/interruptible_handler.hpp"

#include "method/response/penalty_response.hpp"

namespace tcb {

InterruptibleHandler::InterruptibleHandler(Stale stale, std::int64_t keep_lost_cycles)
    : m_stale(stale), m_keep_lost_cycles(stale == Stale::Track ? keep_lost_cycles : 0) {}

std::optional<InterruptibleHandler::StaleForce> InterruptibleHandler::stale_force(const World& world,
                                                                                  std::int32_t object,
                                                                                  std::int32_t vertex) {
  if (!m_has_history[object][vertex] || m_stale == Stale::Nothing) return std::nullopt;
  if (m_stale == Stale::Extrapolate) {
    ForceHistory& h = m_history[object][vertex];
    return StaleForce{h.contact, extrapolated_force(h, m_step), false};
  }
  Contact now = m_tracked[object][vertex];
  now.depth_m = tracked_depth_m(world, now);
  if (!(now.depth_m > 0.0)) return std::nullopt;  // tracked out of contact
  return StaleForce{now, penalty_force(world, now, cycle().settings().response(now.object, now.other), cycle().settings().dt_s),
                    true};
}

void InterruptibleHandler::apply_stale(World& world, const StaleForce& f) const {
  // A tracked depth is a depth-based force of the current positions; an
  // extrapolated force is an estimate. Under implicit response either becomes
  // a link (the estimate's normal part as an equivalent depth), so its spring
  // and damper are integrated implicitly. Either reaction goes to the tet
  // where the point's force last acted.
  if (f.tracked) apply_depth_contact(world, f.where, f.force_n);
  else if (cycle().settings().response_mode == ResponseMode::Explicit) apply_contact_force(world, f.where, f.force_n);
  else add_force_link(world, f.where, f.force_n, cycle().settings().response(f.where.object, f.where.other));
}

void InterruptibleHandler::keep_lost_contacts(const std::vector<Contact>& contacts) {
  // A point with a tracked contact that this cycle did not find (or found
  // without a depth) keeps it for m_keep_lost_cycles more cycles; found with
  // a depth, its count starts again.
  for (std::size_t b = 0; b < m_lost_cycles.size(); ++b)
    for (std::size_t v = 0; v < m_lost_cycles[b].size(); ++v)
      if (m_has_history[b][v] && ++m_lost_cycles[b][v] > m_keep_lost_cycles) m_has_history[b][v] = 0;
  for (const Contact& c : contacts)
    if (c.depth_source != DepthSource::None) m_lost_cycles[c.object][c.vertex] = 0;
}

void InterruptibleHandler::init(const World& world, const CollisionSettings& settings) {
  CycleHandler::init(world, settings);
  for (const Body& b : world.bodies) {
    m_history.emplace_back(b.x_m.size());
    m_has_history.emplace_back(b.x_m.size(), 0);
    m_applied.emplace_back(b.x_m.size(), 0);
    m_tracked.emplace_back(m_stale == Stale::Track ? b.x_m.size() : 0);
    m_lost_cycles.emplace_back(m_keep_lost_cycles > 0 ? b.x_m.size() : 0, 0);
  }
}

StepReport InterruptibleHandler::step(World& world, Budget& budget) {
  ++m_step;
  if (!m_in_progress) {
    mutable_cycle().begin(world);
    m_cycle_start = m_step;
    m_in_progress = true;
  }
  const std::uint64_t before = budget.spent();
  const bool done = mutable_cycle().advance(world, budget);
  StepReport report;
  report.work_units = budget.spent() - before;
  report.cycle = cycle().number();
  report.cycle_done = done;

  const auto& contacts = cycle().contacts();
  const std::size_t with_force = cycle().forces_computed();
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const Contact& c = contacts[i];
    m_applied[c.object][c.vertex] = m_step;  // decided here, so the history loop below leaves it alone
    if (c.separated) continue;               // left the object since detection: no force
    if (c.depth_source != DepthSource::None) {
      const ResponseParams& params = cycle().settings().response(c.object, c.other);
      if (m_stale == Stale::Track) {
        // The depth carried from the step it was computed in to the current
        // positions (unchanged within that step), and remembered with its r0.
        m_tracked[c.object][c.vertex] = c;
        Contact now = c;
        now.depth_m = tracked_depth_m(world, c);
        // Moved out along the normal since the depth was computed: no force. A
        // contact that has not moved gets full's force whatever its depth (its
        // damper may push even at depth 0), so no budget stays bit for bit full.
        if (!(now.depth_m > 0.0) && contact_offset_m(world, c) != c.depth_offset_m) continue;
        apply_depth_contact(world, now, penalty_force(world, now, params, cycle().settings().dt_s));
      } else {
        const Vec3 f = i < with_force ? c.force_n : penalty_force(world, c, params, cycle().settings().dt_s);
        apply_depth_contact(world, c, f);
      }
      ++report.exact_forces;
      report.exact_points.emplace_back(c.object, c.vertex);
    } else if (!done) {
      if (const auto f = stale_force(world, c.object, c.vertex)) {
        apply_stale(world, *f);
        ++report.estimated_forces;
      }
    }
  }
  if (!done && m_stale != Stale::Nothing) {
    // Points in contact in earlier cycles that this cycle has not reached yet.
    for (std::size_t b = 0; b < m_history.size(); ++b)
      for (std::size_t v = 0; v < m_history[b].size(); ++v) {
        if (!m_has_history[b][v] || m_applied[b][v] == m_step) continue;
        const auto object = static_cast<std::int32_t>(b), vertex = static_cast<std::int32_t>(v);
        if (const auto f = stale_force(world, object, vertex)) {
          apply_stale(world, *f);
          ++report.estimated_forces;
        }
      }
  }
  if (done) {
    const std::int64_t cycle_steps = m_step - m_cycle_start + 1;
    if (m_keep_lost_cycles > 0) keep_lost_contacts(contacts);
    else
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
  report.depth_fallback = done ? cycle().depth_fallback() : 0;
  return report;
}

}  // namespace tcb
