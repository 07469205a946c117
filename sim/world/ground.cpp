#include "sim/world/ground.hpp"

#include <algorithm>
#include <cmath>

namespace tcb {

std::size_t apply_ground(const GroundPlane& ground, std::span<Vec3> x, std::span<Vec3> v) {
  std::size_t touched = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!(x[i].y() < ground.height_m)) continue;
    ++touched;
    x[i].y() = ground.height_m;
    const double vn = v[i].y();
    if (vn >= 0.0) continue;
    v[i].y() = 0.0;
    const double tangential = std::hypot(v[i].x(), v[i].z());
    const double reduction = ground.friction * -vn;
    const double keep = tangential > reduction ? (tangential - reduction) / tangential : 0.0;
    v[i].x() *= keep;
    v[i].z() *= keep;
  }
  return touched;
}

}  // namespace tcb
