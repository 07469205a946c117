// orient3d's stages on the inputs that reach past its filter and shortcut:
// near-coplanar points of one binade (a, b, c in [1, 2), so their
// differences are exact; d on their plane, computed in floating point and
// moved 0 .. 2 ulps a coordinate: the plates20 kind of contact, where a
// resting plate's vertices lie within rounding of the plate below), kept
// where orient3d's filter cannot decide.
//   BM_Orient3dPath/0  the exact expansions (orient3d_exact)
//   BM_Orient3dPath/1  the summation stage, fused multiply-add if available
//   BM_Orient3dPath/2  the summation stage with Dekker's products
//   BM_Orient3dPath/3  orient3d itself (filter, shortcut, stage, expansions)
// s_per_call: time a call; decided: the share the stage decided (the
// others would go on to the expansions). The same 20,000 inputs in every
// benchmark; they stop with an error if a path's sign differs from the
// expansions'.
//   build/release/experiments/micro/micro_orient3d
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "sim/geometry/orient3d.hpp"

namespace {

using V = Eigen::Vector3d;

const std::vector<V>& near_coplanar() {
  static const std::vector<V> points = [] {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> unit(1.0, 2.0), w(-0.4, 0.4);
    std::uniform_int_distribution<int> ulps(-2, 2);
    std::vector<V> p;
    while (p.size() < 4 * 20000) {
      const V a(unit(rng), unit(rng), unit(rng)), b(unit(rng), unit(rng), unit(rng)),
          c(unit(rng), unit(rng), unit(rng));
      V d = (a + b + c) / 3.0 + w(rng) * (b - a) + w(rng) * (c - a);
      for (int k = 0; k < 3; ++k)
        for (int n = ulps(rng); n != 0; n += n > 0 ? -1 : 1) d[k] = std::nextafter(d[k], n > 0 ? 2.0 : 1.0);
      if ((d.array() < 1.0).any() || (d.array() >= 2.0).any()) continue;
      // Only what orient3d's filter leaves open: its determinant and error
      // bound (Shewchuk's stage A), in orient3d's order of operations.
      const double adx = a.x() - d.x(), ady = a.y() - d.y(), adz = a.z() - d.z();
      const double bdx = b.x() - d.x(), bdy = b.y() - d.y(), bdz = b.z() - d.z();
      const double cdx = c.x() - d.x(), cdy = c.y() - d.y(), cdz = c.z() - d.z();
      const double bdycdz = bdy * cdz, bdzcdy = bdz * cdy, cdyadz = cdy * adz, cdzady = cdz * ady;
      const double adybdz = ady * bdz, adzbdy = adz * bdy;
      const double det = adx * (bdycdz - bdzcdy) + bdx * (cdyadz - cdzady) + cdx * (adybdz - adzbdy);
      const double permanent = (std::fabs(bdycdz) + std::fabs(bdzcdy)) * std::fabs(adx) +
                               (std::fabs(cdyadz) + std::fabs(cdzady)) * std::fabs(bdx) +
                               (std::fabs(adybdz) + std::fabs(adzbdy)) * std::fabs(cdx);
      const double eps = 0x1p-53;
      if (std::fabs(det) > (7.0 + 56.0 * eps) * eps * permanent) continue;
      p.insert(p.end(), {a, b, c, d});
    }
    return p;
  }();
  return points;
}

void BM_Orient3dPath(benchmark::State& state) {
  const std::vector<V>& p = near_coplanar();
  const std::size_t n = p.size() / 4;
  const int path = static_cast<int>(state.range(0));
  const auto sign_of = [&](std::size_t i, bool& decided) {
    const V* q = &p[4 * i];
    int sign = 0;
    decided = true;
    switch (path) {
      case 0: return tcb::orient3d_exact(q[0], q[1], q[2], q[3]);
      case 1: decided = tcb::orient3d_exact_differences(q[0], q[1], q[2], q[3], sign); return sign;
      case 2:
        decided = tcb::orient3d_exact_differences(q[0], q[1], q[2], q[3], sign, tcb::FusedMultiplyAdd::Never);
        return sign;
      default: return tcb::orient3d(q[0], q[1], q[2], q[3]);
    }
  };
  std::size_t decided_count = 0;
  for (std::size_t i = 0; i < n; ++i) {
    bool decided = false;
    const int sign = sign_of(i, decided);
    decided_count += decided;
    if (decided && sign != tcb::orient3d_exact(p[4 * i], p[4 * i + 1], p[4 * i + 2], p[4 * i + 3])) {
      state.SkipWithError("a sign differs from the exact expansions'");
      return;
    }
  }
  for (auto _ : state) {
    int sum = 0;
    for (std::size_t i = 0; i < n; ++i) {
      bool decided = false;
      sum += sign_of(i, decided);
    }
    benchmark::DoNotOptimize(sum);
  }
  state.counters["s_per_call"] = benchmark::Counter(static_cast<double>(state.iterations() * n),
                                                    benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["decided"] = static_cast<double>(decided_count) / static_cast<double>(n);
}
BENCHMARK(BM_Orient3dPath)->DenseRange(0, 3)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
