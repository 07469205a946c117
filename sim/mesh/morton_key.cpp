#include "sim/mesh/morton_key.hpp"

#include <algorithm>
#include <numeric>

namespace tcb {

std::uint64_t morton_key(const Vec3& p, const Vec3& lo, const Vec3& hi) {
  const auto spread = [](std::uint64_t v) {  // bit i to bit 3i (21 bits)
    v &= 0x1fffff;
    v = (v | v << 32) & 0x1f00000000ffffULL;
    v = (v | v << 16) & 0x1f0000ff0000ffULL;
    v = (v | v << 8) & 0x100f00f00f00f00fULL;
    v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
    v = (v | v << 2) & 0x1249249249249249ULL;
    return v;
  };
  std::uint64_t key = 0;
  for (int a = 0; a < 3; ++a) {
    const double t = (p[a] - lo[a]) / std::max(hi[a] - lo[a], 1e-300);
    // !(t > 0) catches a NaN too: std::clamp would pass it through, and
    // converting a NaN to an integer is undefined.
    const double scaled = !(t > 0.0) ? 0.0 : std::min(t, 1.0) * 2097151.0;
    key |= spread(static_cast<std::uint64_t>(scaled)) << a;
  }
  return key;
}

std::vector<std::uint32_t> along_curve(const std::vector<Vec3>& points, const Vec3& lo, const Vec3& hi) {
  std::vector<std::uint64_t> key(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) key[i] = morton_key(points[i], lo, hi);
  std::vector<std::uint32_t> order(points.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return key[a] < key[b]; });
  return order;
}

std::pair<Vec3, Vec3> bounding_box(const std::vector<Vec3>& points) {
  Vec3 lo = points.at(0), hi = lo;
  for (const Vec3& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return {lo, hi};
}

}  // namespace tcb
