#pragma once
/// The force reference (issue 20, --force-reference every:K): on sampled
/// steps (force_reference_due: one in K, in rotating phase), a shadow `full` handler runs a whole collision cycle on a copy of
/// the state the method just handled (clone_world), and the copy is stepped
/// with its forces; what contacts applied there (Body::applied_contact_force_n,
/// so the definition holds for both response modes: explicit forces, or the
/// implicit links' solved forces) is compared with what the method's contacts
/// applied in the real step (force_error.hpp). The shadow's time is
/// reference_ms, never handling or dynamics time; it changes nothing in the
/// run (the copy is thrown away).
///
/// Columns force_err_rel (relative L2 error of the per-vertex contact force
/// field), force_missed and force_ghost (points), reference_ms; empty on
/// steps not sampled. A sample where full's own cycle overflows the hash is
/// undefined (counted in undefined_samples). Summary `force_error` (null when nothing was sampled):
/// samples; relative_l2 {mean, p50, p95, p99, max} over samples where it is
/// defined, undefined_samples (the reference applied nothing but the method
/// did); angle_deg {mean, p50, p95, p99, max} over all compared points;
/// missed_share and ghost_share {mean, max} over samples with reference
/// (resp. method) points; reference_ms_mean; by_source.<computed|held|
/// extrapolated|tracked> {points, ghost_share, angle_deg_mean, angle_deg_p95,
/// relative_l2_part_mean} (null parts where a source never occurred).

#include <memory>

#include "experiments/metrics/force_error.hpp"
#include "experiments/metrics/meter.hpp"

namespace tcb {

/// Whether step (1-based) is sampled under `every:K`: one step in each
/// window of K, its position in the window rotating (the steps s with
/// s mod K == (s / K) mod K: 11, 22, ..., 99, 100, 111, ... for K = 10; every
/// step for K = 1), so a method with a period (every_nth n, a cycle spanning
/// c steps) is seen in all its phases, not always in the same one.
bool force_reference_due(const OracleSchedule& schedule, std::int64_t step);

class ForceReferenceMeter final : public Meter {
 public:
  explicit ForceReferenceMeter(const RunSetup& run);
  std::vector<ColumnSpec> columns() const override;
  void before_dynamics(StepContext& ctx) override;
  void on_step(StepContext& ctx) override;
  void summarize(Json& summary) const override;

 private:
  OracleSchedule m_schedule;
  double m_dt_s;
  std::unique_ptr<CollisionHandler> m_reference;  // `full`, made on the first sample
  const CollisionSettings* m_settings;
  bool m_sampled = false;  // this step
  bool m_reference_failed = false;  // full's cycle overflowed the hash on this sample
  ForceField m_reference_field;
  std::vector<ForcePoint> m_reference_points;
  double m_reference_ms = 0.0;

  std::int64_t m_samples = 0, m_undefined = 0;
  std::vector<double> m_relative, m_angles, m_missed_share, m_ghost_share, m_reference_ms_all;
  std::array<std::int64_t, kForceSources> m_points{}, m_ghosts{};
  std::array<std::vector<double>, kForceSources> m_source_angles, m_source_parts;
};

}  // namespace tcb
