#include "sim/random/counter_random.hpp"

namespace tcb {

std::uint64_t mix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

std::uint64_t counter_bits(std::uint64_t seed, std::uint64_t stream, std::uint64_t index) {
  return mix64(mix64(mix64(seed) ^ stream) ^ index);
}

double uniform_pm1(std::uint64_t seed, std::uint64_t stream, std::uint64_t index) {
  const std::uint64_t top53 = counter_bits(seed, stream, index) >> 11;
  return static_cast<double>(top53) * 0x1.0p-52 - 1.0;  // [0, 2) - 1
}

double uniform_01(std::uint64_t seed, std::uint64_t stream, std::uint64_t index) {
  return static_cast<double>(counter_bits(seed, stream, index) >> 11) * 0x1.0p-53;
}

}  // namespace tcb
