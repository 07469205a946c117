#pragma once
/// Latency of collision response (summary latency_steps {mean, p95, max} in
/// steps, and unserved_penetrations; the paper: a fast heavy sphere stays
/// correct only with latency <= 2 frames).
///
/// Per vertex, an episode starts at the first oracle step that finds it truly
/// inside another object; its latency is the number of steps from there to the
/// first step in which the handler gives it a depth-based force (0 when both
/// happen in the same step). An episode that ends (the oracle no longer finds
/// the vertex inside) before any depth-based force is counted as unserved, not
/// as a latency. Needs the oracle on every step: with every:K a vertex can
/// leave and re-enter unseen, merging two episodes into one long latency
/// (seen: every_nth n=2 reported 11 steps at every:10, 1 at every), so runs
/// with a sparse oracle report latency_steps as null.

#include <cstdint>
#include <vector>

#include "experiments/metrics/meter.hpp"
#include "oracle/inside_oracle.hpp"
#include "sim/world/world.hpp"

namespace tcb {

class LatencyMeter final : public Meter {
 public:
  /// `oracle_every`: the run's oracle schedule (latency needs every step: 1).
  explicit LatencyMeter(const World& world, std::int64_t oracle_every = 1);
  explicit LatencyMeter(const RunSetup& run) : LatencyMeter(run.world, run.oracle.every) {}
  void before_dynamics(StepContext& ctx) override;
  void summarize(Json& summary) const override;
  /// Call on steps where the oracle ran, with its frame.
  void record_oracle(std::int64_t step, const OracleFrame& frame);
  /// Call every step with the points given a depth-based force in it.
  void record_forces(std::int64_t step, const std::vector<std::pair<std::int32_t, std::int32_t>>& exact_points);
  const std::vector<double>& latencies() const { return m_latencies; }
  std::int64_t unserved() const { return m_unserved; }

 private:
  std::int64_t m_oracle_every;
  std::vector<std::vector<std::int64_t>> m_start;  // episode start step per vertex, -1 none
  std::vector<std::vector<char>> m_served;
  std::vector<double> m_latencies;
  std::int64_t m_unserved = 0;
};

}  // namespace tcb
