#include "method/detection/morton_order.hpp"

#include <algorithm>
#include <numeric>

namespace tcb {

std::vector<std::uint32_t> morton_tet_order(const std::vector<Vec3>& x, const std::vector<Tet>& tets) {
  if (x.empty()) {
    std::vector<std::uint32_t> order(tets.size());
    std::iota(order.begin(), order.end(), 0u);
    return order;
  }
  const auto [lo, hi] = bounding_box(x);  // the vertices' box: a centroid lies in it
  std::vector<Vec3> centroid(tets.size());
  for (std::size_t i = 0; i < tets.size(); ++i) {
    const Tet& t = tets[i];
    centroid[i] = 0.25 * (x[t[0]] + x[t[1]] + x[t[2]] + x[t[3]]);
  }
  return along_curve(centroid, lo, hi);
}

}  // namespace tcb
