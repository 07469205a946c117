#include "method/detection/fast_modulo.hpp"

#include <catch2/catch.hpp>

#include <limits>
#include <random>
#include <vector>

using namespace tcb;

TEST_CASE("fast modulo equals % for every divisor kind and a million numerators", "[hash][fast_modulo]") {
  constexpr std::uint64_t kMax = std::numeric_limits<std::uint64_t>::max();
  // 1, powers of two, small and large primes (table sizes are primes by
  // default, any size a user sets), 2^32 - 1 and 2^32 + 15 (beyond any
  // table), and the largest divisors.
  const std::vector<std::uint64_t> divisors = {1,          2,          3,          7,          31,         1024,
                                               65537,      136403,     2147483647, 4294967291, 4294967295,
                                               4294967311, kMax / 3,   kMax - 1,   kMax};
  std::mt19937_64 rng(20261127);
  std::size_t cases = 0;
  for (const std::uint64_t d : divisors) {
    const FastModulo mod(d);
    REQUIRE(mod.divisor() == d);
    std::vector<std::uint64_t> numerators = {0, 1, d - 1, d, kMax, kMax - 1, kMax / d * d, kMax / d * d - 1};
    if (d < kMax) numerators.push_back(d + 1);
    for (int i = 0; i < 70000; ++i) {
      const std::uint64_t r = rng();
      numerators.push_back(r);
      numerators.push_back(r >> (r & 63));  // small numerators too
    }
    for (const std::uint64_t n : numerators) {
      INFO("n " << n << ", d " << d);
      REQUIRE(mod(n) == n % d);
      ++cases;
    }
  }
  CHECK(cases > 1000000);
}

TEST_CASE("fast modulo refuses a zero divisor", "[hash][fast_modulo]") {
  CHECK_THROWS_AS(FastModulo(0), std::invalid_argument);
}
