#include "experiments/metrics/probe_force_meter.hpp"

#include <algorithm>
#include <cmath>

namespace tcb {

std::vector<ColumnSpec> ProbeForceMeter::columns() const {
  return {{"probe_force_x", "contact force on the driven objects, x (N)"},
          {"probe_force_y", "contact force on the driven objects, y (N)"},
          {"probe_force_z", "contact force on the driven objects, z (N)"}};
}

void ProbeForceMeter::on_step(StepContext& ctx) {
  const auto force = ctx.world.driven_contact_force_n();
  if (!force) return;
  ctx.row.set("probe_force_x", force->x());
  ctx.row.set("probe_force_y", force->y());
  ctx.row.set("probe_force_z", force->z());
  const double magnitude = force->norm();
  m_max = std::max(m_max.value_or(0.0), magnitude);
  if (m_last) {
    const double change = magnitude - *m_last;
    m_change_sum_sq += change * change;
    ++m_changes;
  }
  m_last = magnitude;
}

void ProbeForceMeter::summarize(Json& summary) const {
  summary["probe_force_max"] = m_max ? Json(*m_max) : Json(nullptr);
  summary["probe_force_change_rms"] =
      m_changes > 0 ? Json(std::sqrt(m_change_sum_sq / static_cast<double>(m_changes))) : Json(nullptr);
}

}  // namespace tcb
