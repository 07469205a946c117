#pragma once
// Shared by the dynamics tests: a soft material, randomly moved copies of
// positions, and a comparison of positions bit for bit (+0.0 and -0.0
// differ, a NaN equals its own bits).
#include <cstring>
#include <random>
#include <vector>

#include "sim/dynamics/material.hpp"
#include "sim/mesh/tet_mesh.hpp"

namespace tcb::test {

// Soft enough to bend visibly within a few millisecond steps, and damped.
inline Material soft_material() {
  Material material;
  material.youngs_modulus_pa = 1e5;
  material.damping_mass_per_s = 0.5;
  return material;
}

// x with every vertex moved by up to amount_m along each axis.
inline std::vector<Vec3> perturbed(const std::vector<Vec3>& x, double amount_m, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amount_m, amount_m);
  std::vector<Vec3> y = x;
  for (Vec3& p : y) p += Vec3(u(rng), u(rng), u(rng));
  return y;
}

inline bool same_bits(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec3)) == 0);
}

}  // namespace tcb::test
