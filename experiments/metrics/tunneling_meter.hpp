#pragma once
/// Tunnelling over the run (summary tunneling: object pairs that passed
/// through each other, judged by the oracle's TunnelingJudge, oracle/tunneling.hpp):
/// the pairs interlocked at the start are recorded when the meter is made,
/// every overlap frame the oracle meter computed is noted, and the final state
/// is judged at the end (null when it is not finite).

#include "experiments/metrics/meter.hpp"
#include "oracle/tunneling.hpp"

namespace tcb {

class TunnelingMeter final : public Meter {
 public:
  explicit TunnelingMeter(const RunSetup& run) : m_world(run.world), m_judge(run.world) {}
  void before_dynamics(StepContext& ctx) override;
  void summarize(Json& summary) const override;

 private:
  const World& m_world;
  TunnelingJudge m_judge;
};

}  // namespace tcb
