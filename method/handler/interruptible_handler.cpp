#include "method/handler/interruptible_handler.hpp"

#include <algorithm>

#include "method/handler/heap_bytes.hpp"
#include "method/response/penalty_response.hpp"

namespace tcb {

InterruptibleHandler::InterruptibleHandler(Stale stale, Options options)
    : CycleHandler(DetectionMode::SpatialHash, options.schedule),
      m_stale(stale),
      m_keep_lost_cycles(stale == Stale::Track ? options.keep_lost_cycles : 0),
      m_reserve_apply(options.reserve_apply),
      m_apply_first(options.apply_first) {}

std::optional<InterruptibleHandler::StaleForce> InterruptibleHandler::stale_force(const World& world,
                                                                                  std::int32_t object,
                                                                                  std::int32_t vertex,
                                                                                  HistoryEntry* history) {
  if (history == nullptr || m_stale == Stale::Nothing) return std::nullopt;
  if (m_stale == Stale::Extrapolate) {
    ForceHistory& h = history->history;
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

void InterruptibleHandler::remember_completed_cycle(const std::vector<Contact>& contacts, std::int64_t step,
                                                    std::int64_t cycle_steps) {
  // The history becomes this cycle's depth-based forces. A point it did not
  // find (or found without a depth) loses its history, unless it is a tracked
  // contact kept for m_keep_lost_cycles more cycles; found with a depth, its
  // count starts again. Work is proportional to the points with a history,
  // never to all vertices.
  // Swapped, not moved: the lists keep their capacity from cycle to cycle
  // (no allocation in steady state, and memory_bytes() sees their peak).
  m_histories_before.swap(m_histories);
  m_histories.clear();
  m_histories_new.clear();
  std::vector<HistoryEntry>& before = m_histories_before;
  for (HistoryEntry& e : before)
    e.keep = m_keep_lost_cycles > 0 && ++m_lost_cycles[e.point.first][e.point.second] <= m_keep_lost_cycles;
  // While the lists are rebuilt, m_history_index holds i >= 0 for before[i]
  // and -2 - i for m_histories_new[i].
  for (const Contact& c : contacts) {
    if (c.depth_source == DepthSource::None) continue;
    std::int32_t& index = m_history_index[c.object][c.vertex];
    if (index == -1) {
      index = -2 - static_cast<std::int32_t>(m_histories_new.size());
      m_histories_new.push_back(HistoryEntry{{c.object, c.vertex}, false, ForceHistory{}});
    }
    HistoryEntry& e = index >= 0 ? before[index] : m_histories_new[-2 - index];
    record_depth_force(e.history, c, step, cycle_steps);
    e.keep = true;
    if (m_keep_lost_cycles > 0) m_lost_cycles[c.object][c.vertex] = 0;
  }
  const auto by_point = [](const HistoryEntry& x, const HistoryEntry& y) { return x.point < y.point; };
  if (!std::is_sorted(m_histories_new.begin(), m_histories_new.end(), by_point))
    std::sort(m_histories_new.begin(), m_histories_new.end(), by_point);  // applied in order: sorted
  // Merge the kept entries with the new ones (disjoint), ascending, and index them.
  auto kept = before.begin();
  auto added = m_histories_new.begin();
  const auto take = [this](HistoryEntry& e) {
    m_history_index[e.point.first][e.point.second] = static_cast<std::int32_t>(m_histories.size());
    m_histories.push_back(std::move(e));
  };
  while (kept != before.end() || added != m_histories_new.end()) {
    if (kept != before.end() && !kept->keep) {
      m_history_index[kept->point.first][kept->point.second] = -1;
      ++kept;
    } else if (added == m_histories_new.end() || (kept != before.end() && kept->point < added->point)) {
      take(*kept++);
    } else {
      take(*added++);
    }
  }
}

std::optional<std::size_t> InterruptibleHandler::memory_bytes() const {
  return *CycleHandler::memory_bytes() + heap_bytes(m_histories) + heap_bytes(m_histories_before) +
         heap_bytes(m_histories_new) + heap_bytes(m_history_index) + heap_bytes(m_tracked) +
         heap_bytes(m_lost_cycles) + heap_bytes(m_applied) + heap_bytes(m_completed);
}

void InterruptibleHandler::init(const World& world, const CollisionSettings& settings) {
  CycleHandler::init(world, settings);
  for (const Body& b : world.bodies) {
    m_history_index.emplace_back(b.x_m.size(), -1);
    m_applied.emplace_back(b.x_m.size(), 0);
    m_tracked.emplace_back(m_stale == Stale::Track ? b.x_m.size() : 0);
    m_lost_cycles.emplace_back(m_keep_lost_cycles > 0 ? b.x_m.size() : 0, 0);
  }
}

StepReport InterruptibleHandler::schedule_step(World& world, Budget& budget) {
  ++m_step;
  StepReport report;
  // apply_first: the forces of the cycle as the last step left it (the
  // completed cycle's alone if it completed; none before the first cycle),
  // before this step's first poll: the budget sees applying, and a depth found
  // in this step acts from the next.
  if (m_apply_first && m_cycle_start > 0) apply_forces(world, report, !m_in_progress);
  if (m_remember_pending) {
    // The last step completed a cycle: its forces become the history now,
    // before this step's first poll, where the budget sees the time. Nothing
    // read the history in between, so no result depends on when.
    remember_completed_cycle(cycle().contacts(), m_step - 1, m_remember_cycle_steps);
    m_remember_pending = false;
  }
  const bool reserve = m_reserve_apply && !m_apply_first && budget.kind() == BudgetKind::WallMs;
  // We do not know yet whether this step completes the cycle: reserve for the
  // dearer of the two kinds of step.
  if (reserve) budget.reserve_ms(std::min(std::max(m_apply_ms_done, m_apply_ms_running), 0.5 * budget.limit()));
  if (!m_in_progress) {
    mutable_cycle().begin(world);
    m_cycle_start = m_step;
    m_in_progress = true;
  }
  const std::uint64_t before = budget.spent();
  const bool done = mutable_cycle().advance(world, budget);
  const double cycle_end_ms = reserve ? budget.elapsed_ms() : 0.0;
  report.work_units = budget.spent() - before;
  report.cycle = cycle().number();
  report.cycle_done = done;
  if (!m_apply_first) apply_forces(world, report, done);
  if (done) {
    m_remember_pending = true;
    m_remember_cycle_steps = m_step - m_cycle_start + 1;
    m_completed.clear();
    for (const Contact& c : cycle().contacts())
      if (!c.separated) m_completed.push_back(c);
    m_in_progress = false;
  }
  if (reserve) {
    // What applying took, remembered per kind of step; an old figure fades
    // (x0.99 a step of its kind) so one slow step does not shrink the cycle for
    // good. A faster fade (x0.9) overran more often once a completed cycle's
    // history moved before the next step's first poll: plates20 at 1.7 ms,
    // overshoot p99 5.7-9.4 % against 4.1-7.5 % before; x0.99 gives 4.4-5.5 %.
    double& recent = done ? m_apply_ms_done : m_apply_ms_running;
    recent = std::max(budget.elapsed_ms() - cycle_end_ms, 0.99 * recent);
  }
  report.colliding_points = static_cast<std::int64_t>(m_completed.size());
  report.depth_fallback = done ? cycle().depth_fallback() : 0;
  return report;
}

void InterruptibleHandler::apply_forces(World& world, StepReport& report, bool cycle_complete) {
  const auto& contacts = cycle().contacts();
  const std::size_t with_force = cycle().forces_computed();
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const Contact& c = contacts[i];
    m_applied[c.object][c.vertex] = m_step;  // decided here, so the history loop below leaves it alone
    if (c.separated) continue;               // left the object since detection: no force
    if (c.depth_source != DepthSource::None) {
      const bool fresh = c.depth_step == world.step_index;
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
        apply_depth_contact(world, now);
        report.force_points.push_back({c.object, c.vertex, fresh ? ForceSource::Computed : ForceSource::Tracked});
      } else {
        if (i < with_force) apply_depth_contact(world, c, c.force_n);
        else apply_depth_contact(world, c);  // the cycle has not reached its force yet: computed now
        report.force_points.push_back({c.object, c.vertex, fresh ? ForceSource::Computed : ForceSource::Held});
      }
      ++report.exact_forces;
      report.exact_points.emplace_back(c.object, c.vertex);
    } else if (!cycle_complete) {
      const std::int32_t index = m_history_index[c.object][c.vertex];
      if (const auto f = stale_force(world, c.object, c.vertex, index >= 0 ? &m_histories[index] : nullptr)) {
        apply_stale(world, *f);
        ++report.estimated_forces;
        report.force_points.push_back({c.object, c.vertex, stale_source()});
      }
    }
  }
  if (!cycle_complete && m_stale != Stale::Nothing) {
    // Points in contact in earlier cycles that this cycle has not reached yet
    // (in ascending (body, vertex) order).
    for (HistoryEntry& e : m_histories) {
      const auto [object, vertex] = e.point;
      if (m_applied[object][vertex] == m_step) continue;
      if (const auto f = stale_force(world, object, vertex, &e)) {
        apply_stale(world, *f);
        ++report.estimated_forces;
        report.force_points.push_back({object, vertex, stale_source()});
      }
    }
  }
}

}  // namespace tcb
