#pragma once
/// Random numbers that are the same on every machine and compiler: a
/// counter-based generator (SplitMix64's finaliser applied to a key made of
/// the seed and a counter) and distributions written here. The standard
/// library's distributions are implementation-defined, which would break
/// bit-reproducibility across machines; its engines are not used either.
/// A draw depends only on (seed, stream, index): no state, no order.

#include <cstdint>

namespace tcb {

/// SplitMix64's output function of x (a bijection of 64-bit words).
std::uint64_t mix64(std::uint64_t x);

/// The 64-bit word for (seed, stream, index): mix64 chained over the three.
std::uint64_t counter_bits(std::uint64_t seed, std::uint64_t stream, std::uint64_t index);

/// Uniform in [-1, 1): the word's top 53 bits scaled, exact in double.
double uniform_pm1(std::uint64_t seed, std::uint64_t stream, std::uint64_t index);

/// Uniform in [0, 1): the word's top 53 bits times 2^-53, exact in double.
double uniform_01(std::uint64_t seed, std::uint64_t stream, std::uint64_t index);

}  // namespace tcb
