#include "experiments/metrics/dynamics_meter.hpp"

#include "experiments/metrics/distribution.hpp"

namespace tcb {

std::vector<ColumnSpec> DynamicsMeter::columns() const {
  return {{"kinetic_energy", "kinetic energy of the dynamic bodies after the step (J)"},
          {"dynamics_ms", "wall time of integrating the world (ms)"},
          {"max_speed", "speed of the fastest vertex after the step (m/s)"},
          {"solver_iterations", "linear solver iterations this step, summed over the bodies"}};
}

void DynamicsMeter::on_step(StepContext& ctx) {
  std::int64_t iterations = 0;
  for (const Body& b : ctx.world.bodies) {
    if (!b.model) continue;
    iterations += b.model->last_solver_iterations();
    if (!b.model->last_solve_converged()) ++m_unconverged_steps;  // counted per body, as always
  }
  ctx.row.set("kinetic_energy", ctx.kinetic_energy_j);
  ctx.row.set("dynamics_ms", ctx.dynamics_ms);
  ctx.row.set("max_speed", ctx.max_speed_m_per_s);
  ctx.row.set("solver_iterations", iterations);
  m_dynamics_ms.push_back(ctx.dynamics_ms);
  m_iterations.push_back(static_cast<double>(iterations));
}

void DynamicsMeter::summarize(Json& summary) const {
  summary["dynamics_ms"] = distribution_json(m_dynamics_ms);
  summary["kinetic_energy_final"] = m_world.kinetic_energy_j();
  const Distribution iterations = tcb::summarize(m_iterations);
  summary["solver"] = {{"iterations_mean", iterations.mean},
                       {"iterations_max", iterations.max},
                       {"unconverged_steps", m_unconverged_steps}};
}

}  // namespace tcb
