#include "experiments/metrics/latency.hpp"

namespace tcb {

LatencyMeter::LatencyMeter(const World& world) {
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

}  // namespace tcb
