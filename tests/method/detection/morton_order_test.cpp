// The tet order along a Morton curve (the keys: tests/sim/mesh/morton_key_test.cpp):
// a layout, so what matters is that it is a permutation, deterministic and local.
#include "method/detection/morton_order.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>

using namespace tcb;

TEST_CASE("the Morton tet order is a permutation, stable on ties, and puts a lattice's neighbours near each other",
          "[detection][morton]") {
  // A lattice of n^3 points, one degenerate 'tet' per point (its four
  // vertices the point itself), numbered row by row as mesh files often are.
  const int n = 16;
  std::vector<Vec3> x;
  std::vector<Tet> tets;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const auto v = static_cast<std::int32_t>(x.size());
        x.emplace_back(i, j, k);
        tets.push_back({v, v, v, v});
      }
  const std::vector<std::uint32_t> order = morton_tet_order(x, tets);
  // Sorted, the order is 0 .. n^3 - 1 (a permutation): the file's order.
  std::vector<std::uint32_t> file_order = order;
  std::sort(file_order.begin(), file_order.end());
  for (std::size_t i = 0; i < file_order.size(); ++i) REQUIRE(file_order[i] == i);
  // Locality: a run of 64 consecutive tets spans a small block along the
  // curve (4 x 4 x 4 where the quantisation keeps the lattice's bits), where
  // the file's row order spans whole rows (4 x 16 along one axis).
  const auto mean_span = [&](const std::vector<std::uint32_t>& ranks) {
    double sum = 0.0;
    for (std::size_t r = 0; r < ranks.size(); r += 64) {
      Vec3 lo = x[ranks[r]], hi = lo;
      for (std::size_t s = r; s < r + 64; ++s) {
        lo = lo.cwiseMin(x[ranks[s]]);
        hi = hi.cwiseMax(x[ranks[s]]);
      }
      sum += (hi - lo).maxCoeff();
    }
    return sum / static_cast<double>(ranks.size() / 64);
  };
  INFO("mean span of 64 along the curve " << mean_span(order) << ", in file order " << mean_span(file_order));
  CHECK(mean_span(file_order) == 15.0);
  CHECK(mean_span(order) < 6.0);
  CHECK(order != file_order);  // not the file's order: the layout changes something
  // Ties keep index order: every tet at one point.
  const std::vector<Vec3> one{Vec3(1.0, 2.0, 3.0)};
  const std::vector<Tet> same(5, Tet{0, 0, 0, 0});
  CHECK(morton_tet_order(one, same) == std::vector<std::uint32_t>{0, 1, 2, 3, 4});
  CHECK(morton_tet_order({}, {}).empty());
}
