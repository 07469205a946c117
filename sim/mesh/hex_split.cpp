#include "sim/mesh/hex_split.hpp"

#include <algorithm>

namespace tcb {

std::vector<Tet> split_hexahedra(const std::vector<Hex>& hexes) {
  // The six quads of a hex, wound outward for the documented convention.
  static constexpr int kQuads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                       {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  std::vector<Tet> tets;
  tets.reserve(hexes.size() * 6);
  for (const Hex& h : hexes) {
    const int apex = static_cast<int>(std::min_element(h.begin(), h.end()) - h.begin());
    for (const auto& quad : kQuads) {
      if (std::find(std::begin(quad), std::end(quad), apex) != std::end(quad)) continue;
      int m = 0;  // corner of the quad holding its smallest global index
      for (int k = 1; k < 4; ++k)
        if (h[quad[k]] < h[quad[m]]) m = k;
      const std::int32_t q0 = h[quad[m]], q1 = h[quad[(m + 1) % 4]], q2 = h[quad[(m + 2) % 4]],
                         q3 = h[quad[(m + 3) % 4]];
      // Outward triangle (a, b, c) with the apex behind it: (a, c, b, apex) is positive.
      tets.push_back({q0, q2, q1, h[apex]});
      tets.push_back({q0, q3, q2, h[apex]});
    }
  }
  return tets;
}

}  // namespace tcb
