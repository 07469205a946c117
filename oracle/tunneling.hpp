#pragma once
/// Tunnelling (docs/contract.md summary `tunneling`): object pairs that ended up
/// passing through each other. Part of the oracle: independent of method/.
///
/// A pair (distinct bodies, not both passive) counts when
/// - at the end of the run the centre of mass of one lies strictly inside the
///   other (exact: Side_of_triangle_mesh on a closed surface, the other's
///   tets otherwise, tet_inside.hpp), or
/// - on some oracle frame, or at the end, their exact overlap volume exceeded
///   half the enclosed volume of the smaller of the two (volumes measured on
///   the initial state, overlap_volume.hpp).
/// Pairs that meet either criterion at the start are interlocked by
/// construction and never count. A pair whose volumes cannot be measured
/// (surface fails the exact guard) is judged by centres only, and this is
/// listed in `unmeasured`. Each pair counts at most once.

#include <set>
#include <string>
#include <vector>

#include "oracle/overlap_volume.hpp"
#include "sim/world/world.hpp"

namespace tcb {

struct TunnelingResult {
  std::int64_t pairs = 0;
  std::vector<std::string> unmeasured;
};

using BodyPair = std::pair<std::size_t, std::size_t>;
using BodyPairs = std::vector<BodyPair>;

/// Sorted (a, b), a < b, where one centre lies strictly inside the other.
BodyPairs centres_inside_pairs(const World& world);

class TunnelingJudge {
 public:
  /// Records the initial volumes and the pairs interlocked at the start.
  explicit TunnelingJudge(const World& initial);
  /// Notes the pairs whose overlap in `frame` exceeds half the smaller object.
  void record_overlaps(const OverlapFrame& frame);
  /// Judges the final state and returns the count over the whole run.
  TunnelingResult finish(const World& final_world);

  const BodyPairs& interlocked() const { return m_interlocked; }

 private:
  BodyPairs deep_overlaps(const OverlapFrame& frame) const;

  std::vector<double> m_volume_m3;  ///< initial enclosed volume per body (NaN: unmeasurable)
  BodyPairs m_interlocked;
  std::set<BodyPair> m_tunnelled;
};

}  // namespace tcb
