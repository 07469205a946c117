#pragma once
/// Work units: the fixed cost each unit of collision work charges, so a
/// budget in work units (and the work_units column) is identical on every
/// machine and every repetition. One unit stands for roughly one exact
/// primitive test; the counts depend only on positions, never on timing.

#include <cstdint>

namespace tcb::work {

inline constexpr std::uint64_t kCellInsert = 1;     ///< one tet or triangle entered into one hash cell
inline constexpr std::uint64_t kPointQuery = 1;     ///< hashing one point (plus one per candidate below)
inline constexpr std::uint64_t kTetBox = 1;        ///< one tet's box recomputed and checked against its cells (rehash_stale)
inline constexpr std::uint64_t kCandidate = 1;      ///< one point-in-tet or edge-triangle test
inline constexpr std::uint64_t kBorderPoint = 1;    ///< one colliding point's border-edge work (plus candidates)
inline constexpr std::uint64_t kPropagation = 1;    ///< one propagated point (plus one per neighbour read)
inline constexpr std::uint64_t kNeighbour = 1;
inline constexpr std::uint64_t kForce = 1;          ///< one penalty force
inline constexpr std::uint64_t kPrioritize = 1;     ///< one point's place in the fastest-first order
/// One forward pass of the neural detector (method/neural/neural_handler.hpp):
/// a few microseconds whatever the mesh size, against roughly 0.1-0.5 us per
/// unit above; the unit counts the task, not its time.
inline constexpr std::uint64_t kNetworkEvaluation = 1;

}  // namespace tcb::work
