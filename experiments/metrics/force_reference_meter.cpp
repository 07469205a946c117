#include "experiments/metrics/force_reference_meter.hpp"

#include <chrono>
#include <cmath>

#include "baselines/registry.hpp"
#include "experiments/metrics/distribution.hpp"
#include "method/detection/spatial_hash.hpp"

namespace tcb {
namespace {

ForceField applied_field(const World& world) {
  ForceField field;
  field.reserve(world.bodies.size());
  for (const Body& b : world.bodies) field.push_back(b.applied_contact_force_n);
  return field;
}

}  // namespace

ForceReferenceMeter::ForceReferenceMeter(const RunSetup& run)
    : m_schedule(run.force_reference), m_dt_s(run.scene.world.dt_s), m_settings(run.collision) {}

std::vector<ColumnSpec> ForceReferenceMeter::columns() const {
  return {{"force_err_rel", "relative L2 error of the contact force field against full handling from the same state"},
          {"force_missed", "points full handling gave a force and the method did not"},
          {"force_ghost", "points the method gave a force and full handling did not"},
          {"reference_ms", "wall time of the force reference (shadow full cycle and step); never handling time (ms)"}};
}

bool force_reference_due(const OracleSchedule& schedule, std::int64_t step) {
  const std::int64_t k = schedule.every;
  return k > 0 && step % k == (step / k) % k;
}

void ForceReferenceMeter::before_dynamics(StepContext& ctx) {
  m_sampled = force_reference_due(m_schedule, ctx.step) && m_settings != nullptr;
  if (!m_sampled) return;
  const auto start = std::chrono::steady_clock::now();
  World shadow = clone_world(ctx.world);
  // The copy carries the method's forces and links for this step: drop them.
  for (Body& b : shadow.bodies) std::fill(b.contact_force_n.begin(), b.contact_force_n.end(), Vec3::Zero());
  shadow.contact_links.clear();
  if (!m_reference) {
    const MethodInfo& full = find_method("full");
    m_reference = full.make(MethodSettings(full.settings));
    m_reference->init(shadow, *m_settings);
  }
  Budget unlimited = Budget::unlimited();
  StepReport report;
  try {
    report = m_reference->step(shadow, unlimited);
  } catch (const HashOverflow&) {
    // Full cannot handle this state (the run's own handler may still): no
    // reference, an undefined sample, and the run goes on.
    m_reference_failed = true;
    m_reference_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return;
  }
  m_reference_failed = false;
  shadow.step(m_dt_s);
  m_reference_field = applied_field(shadow);
  m_reference_points = std::move(report.force_points);
  m_reference_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

void ForceReferenceMeter::on_step(StepContext& ctx) {
  if (!m_sampled) return;
  if (m_reference_failed) {
    ++m_samples;
    ++m_undefined;
    ctx.row.set("reference_ms", m_reference_ms);
    return;
  }
  const ForceError e = compare_forces(applied_field(ctx.world), ctx.report.force_points, m_reference_field,
                                      m_reference_points);
  ++m_samples;
  if (e.relative_l2) {
    ctx.row.set("force_err_rel", *e.relative_l2);
    m_relative.push_back(*e.relative_l2);
  } else {
    ++m_undefined;
  }
  ctx.row.set("force_missed", e.missed);
  ctx.row.set("force_ghost", e.ghosts);
  ctx.row.set("reference_ms", m_reference_ms);
  m_reference_ms_all.push_back(m_reference_ms);
  m_angles.insert(m_angles.end(), e.angle_deg.begin(), e.angle_deg.end());
  if (e.reference_points > 0) m_missed_share.push_back(static_cast<double>(e.missed) / static_cast<double>(e.reference_points));
  if (e.applied_points > 0) m_ghost_share.push_back(static_cast<double>(e.ghosts) / static_cast<double>(e.applied_points));
  for (std::size_t s = 0; s < kForceSources; ++s) {
    const SourceForceError& part = e.by_source[s];
    m_points[s] += part.points;
    m_ghosts[s] += part.ghosts;
    m_source_angles[s].insert(m_source_angles[s].end(), part.angle_deg.begin(), part.angle_deg.end());
    if (part.points > 0 && e.reference_norm_n > 0.0)
      m_source_parts[s].push_back(std::sqrt(part.squared_error_n2) / e.reference_norm_n);
  }
}

void ForceReferenceMeter::summarize(Json& summary) const {
  if (m_samples == 0) {
    summary["force_error"] = nullptr;
    return;
  }
  const auto mean_max = [](const std::vector<double>& v) {
    if (v.empty()) return Json(nullptr);
    const Distribution d = tcb::summarize(v);
    return Json{{"mean", d.mean}, {"max", d.max}};
  };
  Json by_source = Json::object();
  for (std::size_t s = 0; s < kForceSources; ++s) {
    Json part = {{"points", m_points[s]},
                 {"ghost_share", m_points[s] > 0 ? Json(static_cast<double>(m_ghosts[s]) / static_cast<double>(m_points[s]))
                                                 : Json(nullptr)}};
    const Distribution angles = tcb::summarize(m_source_angles[s]);
    part["angle_deg_mean"] = angles.count > 0 ? Json(angles.mean) : Json(nullptr);
    part["angle_deg_p95"] = angles.count > 0 ? Json(angles.p95) : Json(nullptr);
    part["relative_l2_part_mean"] = m_source_parts[s].empty() ? Json(nullptr) : Json(tcb::summarize(m_source_parts[s]).mean);
    by_source[force_source_name(static_cast<ForceSource>(s))] = part;
  }
  summary["force_error"] = {{"samples", m_samples},
                            {"relative_l2", distribution_json(m_relative)},
                            {"undefined_samples", m_undefined},
                            {"angle_deg", distribution_json(m_angles)},
                            {"missed_share", mean_max(m_missed_share)},
                            {"ghost_share", mean_max(m_ghost_share)},
                            {"reference_ms_mean", tcb::summarize(m_reference_ms_all).mean},
                            {"by_source", by_source}};
}

}  // namespace tcb
