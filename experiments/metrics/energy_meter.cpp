#include "experiments/metrics/energy_meter.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace tcb {

double available_energy_j(const World& world) {
  double energy = world.kinetic_energy_j() + world.elastic_energy_j();
  const double g = world.gravity_m_per_s2.norm();
  if (g == 0.0) return energy;
  const Vec3 up = -world.gravity_m_per_s2 / g;
  double lowest = std::numeric_limits<double>::infinity();
  if (world.ground) {
    lowest = world.ground->height_m * up.y();  // the plane y = height, measured along up
  } else {
    for (const Body& b : world.bodies)
      for (const Vec3& x : b.x_m) lowest = std::min(lowest, up.dot(x));
  }
  for (const Body& b : world.bodies) {
    if (b.passive) continue;
    for (std::size_t i = 0; i < b.x_m.size(); ++i)
      energy += b.mass_kg[i] * g * std::max(0.0, up.dot(b.x_m[i]) - lowest);
  }
  return energy;
}

EnergyMeter::EnergyMeter(const RunSetup& run)
    : m_world(run.world),
      m_bound(run.scene.max_energy_gain),
      m_initial_j(run.world.total_energy_j()),
      m_available0_j(available_energy_j(run.world)),
      m_final_j(m_initial_j) {}

std::vector<ColumnSpec> EnergyMeter::columns() const {
  return {{"total_energy", "kinetic + elastic + gravitational energy of the dynamic bodies after the step (J)"},
          {"driven_work", "work the driven bodies did on the dynamic ones through their contacts so far (J)"}};
}

void EnergyMeter::on_step(StepContext& ctx) {
  const double motion = ctx.kinetic_energy_j + ctx.world.gravity_potential_j();
  const double energy = motion + ctx.world.elastic_energy_j();
  const double work = ctx.world.driven_work_j;
  ctx.row.set("total_energy", energy);
  ctx.row.set("driven_work", work);
  m_final_j = energy;
  if (!std::isfinite(energy)) return;  // the stability meter names a non-finite state
  m_work_max_j = std::max(m_work_max_j, work);
  const double gain = energy - m_initial_j - work;
  const double motion_gain = motion - m_initial_j - work;
  m_gain_max_j = std::max(m_gain_max_j, gain);
  const double available = m_available0_j + m_work_max_j;
  if (!(available > 0.0)) return;
  m_judged = true;
  if (gain / available > m_gain_max_rel) {
    m_gain_max_rel = gain / available;
    m_gain_step = ctx.step;
  }
  if (motion_gain / available > m_motion_gain_max_rel) {
    m_motion_gain_max_rel = motion_gain / available;
    m_motion_gain_step = ctx.step;
  }
  if (motion_gain / available > m_bound && ctx.unstable.empty())
    ctx.unstable = fmt::format(
        "energy rose by {:.4g} J at step {}: the bodies' motion and height held {:.3g} of the {:.4g} J the run "
        "started with and was given more than that, above the scene's max_energy_gain {:g} (initial {:.4g} J, "
        "kinetic + gravitational now {:.4g} J, work of driven bodies {:.4g} J)",
        motion_gain, ctx.step, motion_gain / available, available, m_bound, m_initial_j, motion, work);
}

void EnergyMeter::summarize(Json& summary) const {
  summary["energy_gain"] = m_judged ? Json(m_gain_max_rel) : Json(nullptr);
  summary["motion_energy_gain"] = m_judged ? Json(m_motion_gain_max_rel) : Json(nullptr);
  summary["energy"] = {{"initial_j", m_initial_j},
                       {"final_j", m_final_j},
                       {"available_j", m_available0_j + m_work_max_j},
                       {"gain_max_j", m_gain_max_j},
                       {"gain_step", m_gain_step},
                       {"motion_gain_step", m_motion_gain_step},
                       {"driven_work_j", m_world.driven_work_j},
                       {"bound", m_bound}};
}

}  // namespace tcb
