#pragma once
/// The simulated world itself: integration time, energy, solver effort.
/// Columns kinetic_energy (J, dynamic bodies), dynamics_ms (ms, world.step),
/// max_speed (m/s, the fastest vertex; NaN when a state is not finite),
/// solver_iterations (CG iterations summed over the bodies). Summary
/// dynamics_ms {mean, p50, p95, p99, max}, kinetic_energy_final (J), solver
/// {iterations_mean, iterations_max, unconverged_steps}.

#include "experiments/metrics/meter.hpp"

namespace tcb {

class DynamicsMeter final : public Meter {
 public:
  explicit DynamicsMeter(const RunSetup& run) : m_world(run.world) {}
  std::vector<ColumnSpec> columns() const override;
  void on_step(StepContext& ctx) override;
  void summarize(Json& summary) const override;

 private:
  const World& m_world;
  std::vector<double> m_dynamics_ms, m_iterations;
  std::int64_t m_unconverged_steps = 0;
};

}  // namespace tcb
