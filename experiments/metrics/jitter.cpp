#include "experiments/metrics/jitter.hpp"

#include <cmath>

namespace tcb {

void JitterMeter::record(const World& world, std::int64_t step, std::int64_t steps_total) {
  if (!in_settled_half(step, steps_total)) return;
  for (const Body& b : world.bodies) {
    if (b.passive) continue;
    double momentum = 0.0, mass = 0.0;
    for (std::size_t i = 0; i < b.x_m.size(); ++i) {
      momentum += b.mass_kg[i] * b.v_m_per_s[i].y();
      mass += b.mass_kg[i];
    }
    if (mass <= 0.0) continue;
    const double v = momentum / mass;
    m_sum_sq += v * v;
    ++m_samples;
  }
}

double JitterMeter::rms_m_per_s() const {
  return m_samples ? std::sqrt(m_sum_sq / static_cast<double>(m_samples)) : 0.0;
}

void JitterMeter::summarize(Json& summary) const {
  summary["jitter"] = !m_enabled || m_samples == 0 ? Json(nullptr) : Json(rms_m_per_s());
}

}  // namespace tcb
