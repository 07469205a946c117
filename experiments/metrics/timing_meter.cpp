#include "experiments/metrics/timing_meter.hpp"

#include "experiments/metrics/distribution.hpp"
#include "experiments/metrics/timing_quality.hpp"
#include "experiments/run/thread_clock.hpp"
#include "experiments/run/timing_floor.hpp"

namespace tcb {

TimingMeter::TimingMeter(const RunSetup& run)
    : m_budget(run.budget),
      m_floor(run.timing_floor && run.budget.kind == BudgetKind::WallMs && run.budget.value > 0.0 &&
              run.budget.value <= kFloorMaxWindowMs),
      m_start(sample_machine()) {}

void TimingMeter::on_step(StepContext& ctx) {
  ++m_steps;
  m_switches += ctx.handling_switches;
  const double base = m_budget.kind == BudgetKind::WallMs && m_budget.value > 0.0 ? m_budget.value : ctx.handling_ms;
  if (is_preempted(ctx.handling_ms, ctx.handling_cpu_ms, base)) ++m_preempted;
  if (m_floor) m_floor_overshoot_ms.push_back(null_handler_overshoot_ms(m_budget.value));
}

namespace {

// {p50, p99, max} of scale * value.
Meter::Json tail_json(const Distribution& d, double scale) {
  return {{"p50", scale * d.p50}, {"p99", scale * d.p99}, {"max", scale * d.max}};
}

}  // namespace

void TimingMeter::summarize(Json& summary) const {
  const MachineSample end = sample_machine();
  TimingEvidence e;
  e.steps = m_steps;
  e.preempted_steps = m_preempted;
  e.other_busy_cpus = other_busy_cpus(m_start, end);
  e.cpus = online_cpus();
  e.loadavg_start = m_start.loadavg_1min;
  e.governor = cpu_governor();
  e.pinned_cpu = pinned_cpu();
  Json floor(nullptr);
  if (!m_floor_overshoot_ms.empty()) {
    const Distribution d = tcb::summarize(m_floor_overshoot_ms);
    floor = {{"windows", m_floor_overshoot_ms.size()},
             {"overshoot_us", tail_json(d, 1000.0)},
             {"overshoot_pct", tail_json(d, 100.0 / m_budget.value)}};
    e.floor_p99_pct = 100.0 * d.p99 / m_budget.value;
  }
  const TimingVerdict v = timing_verdict(e);
  const auto opt = [](const auto& o) { return o ? Json(*o) : Json(nullptr); };
  summary["timing"] = {
      {"verdict", v.noisy ? "noisy" : "quiet"},
      {"reasons", v.reasons},
      {"notes", v.notes},
      {"preempted_steps", m_preempted},
      {"preempted_step_share", m_steps > 0 ? Json(static_cast<double>(m_preempted) / static_cast<double>(m_steps))
                                           : Json(nullptr)},
      {"involuntary_switches", m_switches},
      {"other_busy_cpus", opt(e.other_busy_cpus)},
      {"cpus", e.cpus},
      {"loadavg_1min", {{"start", opt(m_start.loadavg_1min)}, {"end", opt(end.loadavg_1min)}}},
      {"governor", opt(e.governor)},
      {"pinned_cpu", opt(e.pinned_cpu)},
      {"floor", floor}};
}

}  // namespace tcb
