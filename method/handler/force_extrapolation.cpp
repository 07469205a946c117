#include "method/handler/force_extrapolation.hpp"

#include <algorithm>

namespace tcb {

void record_depth_force(ForceHistory& h, const Contact& contact, std::int64_t step, std::int64_t cycle_steps) {
  if (h.has_f1) {
    h.f2 = h.f1;
    h.has_f2 = true;
  }
  h.f1 = contact.force_n;
  h.has_f1 = true;
  h.step_f1 = step;
  h.cycle_steps = std::max<std::int64_t>(cycle_steps, 1);
  h.contact = contact;
  h.stopped = false;
}

Vec3 extrapolated_force(ForceHistory& h, std::int64_t step) {
  if (h.stopped || !h.has_f1) return Vec3::Zero();
  if (!h.has_f2) return h.f1;
  const Vec3 df = (h.f1 - h.f2) / static_cast<double>(h.cycle_steps);
  const Vec3 f = h.f1 + static_cast<double>(step - h.step_f1) * df;
  const bool decreasing = h.f1.squaredNorm() < h.f2.squaredNorm();
  if (decreasing && f.dot(h.f1) < 0.0) {
    h.stopped = true;
    return Vec3::Zero();
  }
  return f;
}

}  // namespace tcb
