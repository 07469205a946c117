#include "experiments/metrics/tunneling_meter.hpp"

#include <cmath>

namespace tcb {

void TunnelingMeter::before_dynamics(StepContext& ctx) {
  if (ctx.overlap) m_judge.record_overlaps(*ctx.overlap);
}

void TunnelingMeter::summarize(Json& summary) const {
  if (!std::isfinite(m_world.max_speed_m_per_s())) {
    summary["tunneling"] = nullptr;  // positions are not finite: nothing to judge
    note_unmeasured(summary, "tunnelling: the final state is not finite");
    return;
  }
  TunnelingJudge judge = m_judge;  // finish() judges the final state; summarize() stays repeatable
  const TunnelingResult tunnelled = judge.finish(m_world);
  summary["tunneling"] = tunnelled.pairs;
  for (const std::string& reason : tunnelled.unmeasured) note_unmeasured(summary, reason);
}

}  // namespace tcb
