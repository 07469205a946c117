#include "experiments/metrics/top_centre_meter.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tcb {

std::optional<double> top_centre_height_m(const World& world) {
  const double g = world.gravity_m_per_s2.norm();
  const Vec3 up = g > 0.0 ? Vec3(-world.gravity_m_per_s2 / g) : Vec3(0.0, 1.0, 0.0);
  std::optional<double> top;
  for (const Body& b : world.bodies)
    if (!b.passive) top = std::max(top.value_or(-std::numeric_limits<double>::infinity()), centre_of_mass_m(b).dot(up));
  return top;
}

void TopCentreMeter::summarize(Json& summary) const {
  const std::optional<double> final_m = top_centre_height_m(m_world);
  summary["top_centre_height_m"] = m_initial && final_m && std::isfinite(*final_m)
                                       ? Json{{"initial", *m_initial}, {"final", *final_m}}
                                       : Json(nullptr);
}

}  // namespace tcb
