#include "sim/dynamics/block_rows.hpp"

#include <stdexcept>

namespace tcb {

BlockRows block_rows_of(std::span<const std::int32_t> outer, std::span<const std::int32_t> inner) {
  if (outer.empty() || (outer.size() - 1) % 3 != 0)
    throw std::invalid_argument("block_rows_of: the row count is not a multiple of 3");
  const std::size_t block_rows = (outer.size() - 1) / 3;
  BlockRows b;
  b.first.reserve(block_rows + 1);
  b.regular.reserve(block_rows);
  b.first.push_back(0);
  for (std::size_t i = 0; i < block_rows; ++i) {
    const std::int32_t* row[3];
    std::int32_t length = outer[3 * i + 1] - outer[3 * i];
    bool regular = length % 3 == 0;
    for (int r = 0; r < 3; ++r) {
      row[r] = inner.data() + outer[3 * i + r];
      regular = regular && outer[3 * i + r + 1] - outer[3 * i + r] == length;
    }
    // Whole blocks: every row lists 3j, 3j+1, 3j+2 for the same j's.
    for (std::int32_t k = 0; regular && k < length; k += 3)
      for (int r = 0; r < 3 && regular; ++r)
        regular = row[r][k] % 3 == 0 && row[r][k] == row[0][k] && row[r][k + 1] == row[0][k] + 1 &&
                  row[r][k + 2] == row[0][k] + 2;
    if (regular)
      for (std::int32_t k = 0; k < length; k += 3) b.columns.push_back(row[0][k]);
    b.regular.push_back(regular ? 1 : 0);
    b.first.push_back(static_cast<std::int32_t>(b.columns.size()));
  }
  return b;
}

void multiply_block_rows(const BlockRows& blocks, const std::int32_t* outer, const std::int32_t* inner,
                         const double* values, const double* x, double* out) {
  const std::size_t block_rows = blocks.regular.size();
  const std::int32_t* columns = blocks.columns.data();
  for (std::size_t i = 0; i < block_rows; ++i) {
    if (!blocks.regular[i]) {
      for (std::size_t row = 3 * i; row < 3 * i + 3; ++row) {
        double sum = 0.0;
        for (std::int32_t k = outer[row]; k < outer[row + 1]; ++k) sum += values[k] * x[inner[k]];
        out[row] = 0.0 + sum;  // Eigen adds the sum to a zeroed result (header)
      }
      continue;
    }
    // The three rows' values lie one after another, each 3 * (blocks) long.
    const std::int32_t length = outer[3 * i + 1] - outer[3 * i];
    const double* v0 = values + outer[3 * i];
    const double* v1 = v0 + length;
    const double* v2 = v1 + length;
    double s0 = 0.0, s1 = 0.0, s2 = 0.0;
    for (std::int32_t b = blocks.first[i]; b < blocks.first[i + 1]; ++b, v0 += 3, v1 += 3, v2 += 3) {
      const double* xb = x + columns[b];
      const double x0 = xb[0], x1 = xb[1], x2 = xb[2];
      // One rounded product and one rounded sum at a time, column by column:
      // Eigen's order (file comment).
      s0 += v0[0] * x0;
      s0 += v0[1] * x1;
      s0 += v0[2] * x2;
      s1 += v1[0] * x0;
      s1 += v1[1] * x1;
      s1 += v1[2] * x2;
      s2 += v2[0] * x0;
      s2 += v2[1] * x1;
      s2 += v2[2] * x2;
    }
    out[3 * i] = 0.0 + s0;
    out[3 * i + 1] = 0.0 + s1;
    out[3 * i + 2] = 0.0 + s2;
  }
}

}  // namespace tcb
