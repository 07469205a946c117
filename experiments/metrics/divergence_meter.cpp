#include "experiments/metrics/divergence_meter.hpp"

#include <algorithm>

#include "sim/io/input_error.hpp"
#include "sim/mesh/curve_numbering.hpp"

namespace tcb {

DivergenceMeter::DivergenceMeter(const RunSetup& run) : m_reference_dir(run.reference_dir) {
  if (m_reference_dir.empty()) return;
  const std::filesystem::path file = m_reference_dir / "trajectory.bin";
  m_reader = std::make_unique<TrajectoryReader>(file);
  const auto& masses = m_reader->masses_kg();
  if (masses.size() != run.world.bodies.size())
    throw InputError(file.string(), 0,
                     "the reference has " + std::to_string(masses.size()) + " bodies, this run " +
                         std::to_string(run.world.bodies.size()) + ": not the same scene");
  for (std::size_t b = 0; b < masses.size(); ++b) {
    if (masses[b].size() != run.world.bodies[b].x_m.size())
      throw InputError(file.string(), 0,
                       "body " + std::to_string(b) + " ('" + run.world.bodies[b].name + "') has " +
                           std::to_string(masses[b].size()) + " vertices in the reference, " +
                           std::to_string(run.world.bodies[b].x_m.size()) + " here: not the same scene");
    m_dynamic.push_back(run.world.bodies[b].passive ? 0 : 1);
  }
  m_next = m_reader->next();
}

std::vector<ColumnSpec> DivergenceMeter::columns() const {
  return {{"div_rms_m", "RMS vertex distance to the reference run at this step (m)"},
          {"div_max_m", "largest vertex distance to the reference run (m)"},
          {"div_com_m", "largest centre-of-mass distance of a body to the reference (m)"},
          {"div_orientation_deg", "largest best-fit rotation of a body against the reference (degrees)"},
          {"div_momentum_n_s", "largest linear momentum difference of a body to the reference (N s)"},
          {"div_angular_momentum_n_m_s", "largest angular momentum difference of a body to the reference (N m s)"}};
}

void DivergenceMeter::on_step(StepContext& ctx) {
  if (!m_reader) return;
  while (m_next && m_next->step < ctx.step) m_next = m_reader->next();
  if (!m_next || m_next->step != ctx.step) return;
  const std::size_t bodies = ctx.world.bodies.size();
  m_x.resize(bodies);
  m_v.resize(bodies);
  for (std::size_t b = 0; b < bodies; ++b) {  // in the file's numbering, as the reference wrote them
    const Body& body = ctx.world.bodies[b];
    as_float32(in_file_order(*body.mesh, body.x_m, m_file_order), m_buffer, m_x[b]);
    as_float32(in_file_order(*body.mesh, body.v_m_per_s, m_file_order), m_buffer, m_v[b]);
  }
  const Divergence d = compare_states({m_x, m_v}, {m_next->x_m, m_next->v_m_per_s}, m_reader->masses_kg(), m_dynamic);
  ctx.row.set("div_rms_m", d.rms_m);
  ctx.row.set("div_max_m", d.max_m);
  ctx.row.set("div_com_m", d.com_drift_m);
  ctx.row.set("div_orientation_deg", d.orientation_drift_deg);
  ctx.row.set("div_momentum_n_s", d.linear_momentum_diff_n_s);
  ctx.row.set("div_angular_momentum_n_m_s", d.angular_momentum_diff_n_m_s);
  m_final = d;
  m_max.rms_m = std::max(m_max.rms_m, d.rms_m);
  m_max.max_m = std::max(m_max.max_m, d.max_m);
  m_max.com_drift_m = std::max(m_max.com_drift_m, d.com_drift_m);
  m_max.orientation_drift_deg = std::max(m_max.orientation_drift_deg, d.orientation_drift_deg);
  m_max.linear_momentum_diff_n_s = std::max(m_max.linear_momentum_diff_n_s, d.linear_momentum_diff_n_s);
  m_max.angular_momentum_diff_n_m_s = std::max(m_max.angular_momentum_diff_n_m_s, d.angular_momentum_diff_n_m_s);
  ++m_compared;
  m_last_step = ctx.step;
  m_next = m_reader->next();
}

void DivergenceMeter::summarize(Json& summary) const {
  if (!m_reader) {
    summary["divergence"] = nullptr;
    return;
  }
  const auto pair = [&](double final_value, double max_value) {
    return m_compared > 0 ? Json{{"final", final_value}, {"max", max_value}} : Json(nullptr);
  };
  summary["divergence"] = {
      {"reference", m_reference_dir.string()},
      {"every", m_reader->every()},
      {"compared_steps", m_compared},
      {"last_step", m_last_step},
      {"rms_m", pair(m_final.rms_m, m_max.rms_m)},
      {"max_m", pair(m_final.max_m, m_max.max_m)},
      {"com_drift_m", pair(m_final.com_drift_m, m_max.com_drift_m)},
      {"orientation_drift_deg", pair(m_final.orientation_drift_deg, m_max.orientation_drift_deg)},
      {"linear_momentum_diff_n_s", pair(m_final.linear_momentum_diff_n_s, m_max.linear_momentum_diff_n_s)},
      {"angular_momentum_diff_n_m_s", pair(m_final.angular_momentum_diff_n_m_s, m_max.angular_momentum_diff_n_m_s)}};
}

}  // namespace tcb
