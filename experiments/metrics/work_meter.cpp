#include "experiments/metrics/work_meter.hpp"

#include <algorithm>

#include "experiments/metrics/distribution.hpp"

namespace tcb {

std::vector<ColumnSpec> WorkMeter::columns() const {
  return {{"work_units", "work units the handler charged this step"},
          {"cycle", "the collision cycle worked on (1-based; 0 none)"},
          {"cycle_done", "1 when a cycle completed in this step"},
          {"colliding_points", "colliding points the method holds after the step"},
          {"exact_forces", "points given a depth-based force computed this step"},
          {"estimated_forces", "points given an estimated, extrapolated, tracked or held force"}};
}

void WorkMeter::on_step(StepContext& ctx) {
  const StepReport& r = ctx.report;
  ctx.row.set("work_units", static_cast<std::int64_t>(r.work_units));
  ctx.row.set("cycle", r.cycle);
  ctx.row.set("cycle_done", std::int64_t{r.cycle_done ? 1 : 0});
  ctx.row.set("colliding_points", r.colliding_points);
  ctx.row.set("exact_forces", r.exact_forces);
  ctx.row.set("estimated_forces", r.estimated_forces);
  m_work_total += r.work_units;
  m_depth_fallback += r.depth_fallback;
  m_colliding_max = std::max(m_colliding_max, r.colliding_points);
  if (r.cycle_done) {
    m_cycle_lengths.push_back(static_cast<double>(ctx.step - m_cycle_start_step + 1));
    m_cycle_start_step = ctx.step + 1;
  }
}

void WorkMeter::summarize(Json& summary) const {
  if (m_cycle_lengths.empty()) {
    summary["cycle_steps"] = nullptr;
  } else {
    const Distribution cycles = tcb::summarize(m_cycle_lengths);
    summary["cycle_steps"] = {{"mean", cycles.mean}, {"max", cycles.max}};
  }
  summary["work_units_total"] = m_work_total;
  summary["colliding_points_max"] = m_colliding_max;
  summary["depth_fallback_points"] = m_depth_fallback;
}

}  // namespace tcb
