#include "experiments/metrics/latency.hpp"

#include "experiments/metrics/distribution.hpp"

namespace tcb {

LatencyMeter::LatencyMeter(const World& world, std::int64_t oracle_every) : m_oracle_every(oracle_every) {
  for (const Body& b : world.bodies) {
    m_start.emplace_back(b.x_m.size(), -1);
    m_served.emplace_back(b.x_m.size(), 0);
  }
}

void LatencyMeter::record_oracle(std::int64_t step, const OracleFrame& frame) {
  std::vector<std::vector<char>> inside(m_start.size());
  for (std::size_t b = 0; b < m_start.size(); ++b) inside[b].assign(m_start[b].size(), 0);
  for (const OraclePoint& p : frame.inside) inside[p.object][p.vertex] = 1;
  for (std::size_t b = 0; b < m_start.size(); ++b)
    for (std::size_t v = 0; v < m_start[b].size(); ++v) {
      if (inside[b][v] && m_start[b][v] < 0) {  // a new episode
        m_start[b][v] = step;
        m_served[b][v] = 0;
      } else if (!inside[b][v] && m_start[b][v] >= 0) {  // the episode ended
        if (!m_served[b][v]) ++m_unserved;
        m_start[b][v] = -1;
      }
    }
}

void LatencyMeter::record_forces(std::int64_t step, const std::vector<std::pair<std::int32_t, std::int32_t>>& points) {
  for (const auto& [b, v] : points) {
    if (m_start[b][v] < 0 || m_served[b][v]) continue;
    m_served[b][v] = 1;
    m_latencies.push_back(static_cast<double>(step - m_start[b][v]));
  }
}

void LatencyMeter::before_dynamics(StepContext& ctx) {
  if (ctx.oracle) record_oracle(ctx.step, *ctx.oracle);
  if (m_oracle_every == 1) record_forces(ctx.step, ctx.report.exact_points);
}

void LatencyMeter::summarize(Json& summary) const {
  // Between sparse oracle steps a vertex can leave and re-enter unseen, which
  // merges episodes and inflates latencies: only an every-step oracle measures it.
  if (m_oracle_every > 1) note_unmeasured(summary, "latency_steps: needs --oracle every (sparse oracle steps merge episodes)");
  if (m_oracle_every != 1) {
    summary["latency_steps"] = nullptr;
    summary["unserved_penetrations"] = nullptr;  // present, like every key, so summary.csv columns line up
    return;
  }
  const Distribution l = tcb::summarize(m_latencies);
  summary["latency_steps"] = m_latencies.empty() ? Json(nullptr) : Json{{"mean", l.mean}, {"p95", l.p95}, {"max", l.max}};
  summary["unserved_penetrations"] = m_unserved;
}

}  // namespace tcb
