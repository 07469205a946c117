#pragma once
/// The implicit step's matrix-vector product, read by 3x3 blocks.
///
/// An FEM system matrix is assembled from 3x3 blocks (one per pair of
/// vertices sharing a tet), so its rows come in triples 3i, 3i+1, 3i+2 that
/// hold the same columns, three by three: 3j, 3j+1, 3j+2 for each neighbour j.
/// Eigen's compressed row-major product reads one column index and one x
/// entry per nonzero; multiply_block_rows() reads one block column per nine
/// nonzeros and the three x entries of that block once for the three rows.
///
/// Contract: the result is bit for bit what Eigen's `out.noalias() = A * x`
/// gives for the same compressed matrix (Eigen 3.4). Each row's sum starts at
/// +0.0 and adds value * x over its nonzeros in ascending column order, one
/// rounded product and one rounded addition at a time, as Eigen's row loop
/// does, and is stored as 0.0 + sum, as Eigen adds it to a zeroed result (a
/// sum can be -0.0 only where products are fused). The project's builds do
/// not fuse multiply-adds (no -march: baseline x86-64 has none); a build that
/// does must contract both loops alike, which
/// tests/sim/dynamics/block_rows_test.cpp would catch if it did not. A block
/// row whose three rows do not share one pattern of whole blocks (a vertex in
/// no tet keeps only its diagonal entries) is multiplied row by row, in the
/// same order. Units are the caller's.

#include <cstdint>
#include <span>
#include <vector>

namespace tcb {

/// Where each block row's blocks are: the block columns (3j) of block row i
/// are columns[first[i] .. first[i + 1]); a row triple that is not made of
/// whole blocks has regular[i] == 0 and no entries in columns.
struct BlockRows {
  std::vector<std::int32_t> first;
  std::vector<std::int32_t> columns;
  std::vector<std::uint8_t> regular;
};

/// The block rows of a compressed (Eigen's isCompressed()) row-major matrix
/// with outer.size() - 1 rows (a multiple of 3; std::invalid_argument
/// otherwise): outer and inner are Eigen's outerIndexPtr() and
/// innerIndexPtr() ranges, each row's columns ascending and unique.
BlockRows block_rows_of(std::span<const std::int32_t> outer, std::span<const std::int32_t> inner);

/// out = A x for the compressed matrix block_rows_of() read (file comment):
/// it reads a row triple's values as three runs one after another, so the
/// matrix must still be compressed, with the same pattern. values is Eigen's
/// valuePtr(); x and out hold one entry per row and must not overlap.
void multiply_block_rows(const BlockRows& blocks, const std::int32_t* outer, const std::int32_t* inner,
                         const double* values, const double* x, double* out);

}  // namespace tcb
