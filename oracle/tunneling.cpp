#include "oracle/tunneling.hpp"

#include <algorithm>
#include <cmath>

namespace tcb {

TunnelingJudge::TunnelingJudge(const World& initial) {
  for (const Body& b : initial.bodies) m_volume_m3.push_back(enclosed_volume_m3(b));
  m_interlocked = centres_inside_pairs(initial);
  const BodyPairs deep = deep_overlaps(compute_overlap_volumes(initial));
  m_interlocked.insert(m_interlocked.end(), deep.begin(), deep.end());
  std::sort(m_interlocked.begin(), m_interlocked.end());
  m_interlocked.erase(std::unique(m_interlocked.begin(), m_interlocked.end()), m_interlocked.end());
}

BodyPairs TunnelingJudge::deep_overlaps(const OverlapFrame& frame) const {
  BodyPairs pairs;
  for (const PairOverlap& p : frame.pairs) {
    const double smaller = std::min(m_volume_m3[p.a], m_volume_m3[p.b]);  // NaN if either is unmeasurable
    if (std::isfinite(smaller) && p.volume_m3 > 0.5 * smaller)
      pairs.emplace_back(static_cast<std::size_t>(p.a), static_cast<std::size_t>(p.b));
  }
  return pairs;
}

void TunnelingJudge::record_overlaps(const OverlapFrame& frame) {
  for (const BodyPair& p : deep_overlaps(frame))
    if (!std::binary_search(m_interlocked.begin(), m_interlocked.end(), p)) m_tunnelled.insert(p);
}

TunnelingResult TunnelingJudge::finish(const World& final_world) {
  TunnelingResult r;
  record_overlaps(compute_overlap_volumes(final_world));
  for (const BodyPair& p : centres_inside_pairs(final_world))
    if (!std::binary_search(m_interlocked.begin(), m_interlocked.end(), p)) m_tunnelled.insert(p);
  r.pairs = static_cast<std::int64_t>(m_tunnelled.size());
  for (std::size_t i = 0; i < m_volume_m3.size(); ++i)
    if (!std::isfinite(m_volume_m3[i]))
      r.unmeasured.push_back("tunnelling of '" + final_world.bodies[i].name +
                             "' judged by centres only (its surface bounds no exact volume)");
  return r;
}

}  // namespace tcb
