#include "method/detection/morton_order.hpp"

#include <algorithm>
#include <numeric>

namespace tcb {

std::vector<std::uint32_t> morton_tet_order(const std::vector<Vec3>& x, const std::vector<Tet>& tets) {
  std::vector<std::uint32_t> order(tets.size());
  std::iota(order.begin(), order.end(), 0u);
  if (x.empty()) return order;
  const auto [lo, hi] = bounding_box(x);
  std::vector<std::uint64_t> key(tets.size());
  for (std::size_t i = 0; i < tets.size(); ++i) {
    const Tet& t = tets[i];
    key[i] = morton_key(0.25 * (x[t[0]] + x[t[1]] + x[t[2]] + x[t[3]]), lo, hi);
  }
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return key[a] < key[b]; });
  return order;
}

}  // namespace tcb
