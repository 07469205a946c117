#pragma once
/// n mod d for 64-bit n and a divisor fixed in advance, without a division
/// instruction: the spatial hash reduces every cell's hash modulo its table
/// size, eight times a tet and once a point query, and a 64-bit division
/// costs tens of cycles where this costs five multiplications.
///
/// Method (Lemire, Kaser and Kurz, "Faster remainder by direct computation",
/// 2019): with c = ceil(2^128 / d), n mod d is the high 64 bits of
/// ((c n) mod 2^128) d. Exact for every 64-bit n and every d >= 1 (their
/// theorem needs 128 >= 64 + log2 d); d = 1 gives c = 0 and the result 0.
/// The test compares it with % over a million random and edge cases.

#include <cstdint>
#include <stdexcept>

namespace tcb {

class FastModulo {
 public:
  FastModulo() = default;
  /// d >= 1 (else std::invalid_argument).
  explicit FastModulo(std::uint64_t d) : m_d(d) {
    if (d == 0) throw std::invalid_argument("FastModulo: the divisor must be at least 1");
    m_c = ~Wide(0) / d + 1;  // ceil(2^128 / d), wrapping to 0 for d = 1
  }
  std::uint64_t divisor() const { return m_d; }
  /// n mod divisor().
  std::uint64_t operator()(std::uint64_t n) const {
    const Wide low = m_c * n;  // mod 2^128
    const Wide bottom = (Wide(static_cast<std::uint64_t>(low)) * m_d) >> 64;
    const Wide top = Wide(static_cast<std::uint64_t>(low >> 64)) * m_d;
    return static_cast<std::uint64_t>((bottom + top) >> 64);
  }

 private:
  using Wide = __uint128_t;  // GCC and Clang on 64-bit targets
  Wide m_c = 0;
  std::uint64_t m_d = 1;
};

}  // namespace tcb
