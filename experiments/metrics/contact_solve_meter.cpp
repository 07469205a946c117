#include "experiments/metrics/contact_solve_meter.hpp"

#include <algorithm>

namespace tcb {

std::vector<ColumnSpec> ContactSolveMeter::columns() const {
  return {{"contact_links", "implicit contact links solved with the bodies this step (0 under explicit response)"}};
}

void ContactSolveMeter::on_step(StepContext& ctx) {
  const ContactSolveStats& s = ctx.world.last_contact_solve;
  ctx.row.set("contact_links", s.links);
  m_links_max = std::max(m_links_max, s.links);
  m_resolve_steps += s.resolved > 0;
  m_dropped += s.dropped;
  m_still_pulling += s.still_pulling;
  m_unconverged += !s.converged;
}

void ContactSolveMeter::summarize(Json& summary) const {
  summary["contact_links_max"] = m_links_max;
  summary["unilateral_resolve_steps"] = m_resolve_steps;
  summary["unilateral_dropped_links"] = m_dropped;
  summary["unilateral_still_pulling"] = m_still_pulling;
  summary["contact_solve_unconverged_steps"] = m_unconverged;
}

}  // namespace tcb
