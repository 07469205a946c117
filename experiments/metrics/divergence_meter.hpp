#pragma once
/// Divergence from a reference run (issue 20, --reference DIR): on every
/// step the reference recorded in DIR/trajectory.bin (its --trajectory K),
/// this run's state is compared with the reference's (divergence.hpp). Both
/// sides are read at float32 precision, so a run compared with its own
/// trajectory gives exactly 0. A reference with other bodies or vertex
/// counts is an input error (exit 2) before the run starts; a shorter one
/// is compared as far as it goes.
///
/// Columns div_rms_m, div_max_m, div_com_m, div_orientation_deg,
/// div_momentum_n_s, div_angular_momentum_n_m_s; empty on steps not
/// compared. Summary `divergence` (null without --reference): reference (the
/// directory as given), every, compared_steps, last_step, and per measure
/// {final, max}: rms_m, max_m, com_drift_m, orientation_drift_deg,
/// linear_momentum_diff_n_s, angular_momentum_diff_n_m_s. Chaotic scenes
/// (a stack) diverge under any perturbation: judge a run's divergence
/// against the reference's own under a tiny one ([perturb] position, the
/// noise floor; docs/contract.md).

#include <filesystem>
#include <memory>
#include <optional>

#include "experiments/metrics/divergence.hpp"
#include "experiments/metrics/meter.hpp"
#include "experiments/results/trajectory_file.hpp"

namespace tcb {

class DivergenceMeter final : public Meter {
 public:
  explicit DivergenceMeter(const RunSetup& run);
  std::vector<ColumnSpec> columns() const override;
  void on_step(StepContext& ctx) override;
  void summarize(Json& summary) const override;

 private:
  std::filesystem::path m_reference_dir;
  std::unique_ptr<TrajectoryReader> m_reader;
  std::optional<TrajectoryFrame> m_next;  // the reference's next frame
  std::vector<char> m_dynamic;
  std::vector<std::vector<Vec3>> m_x, m_v;  // this run's state at float32 precision
  std::vector<float> m_buffer;
  std::vector<Vec3> m_file_order;  // a renumbered body's state in its file's order, as the reference has it
  std::int64_t m_compared = 0, m_last_step = 0;
  Divergence m_final, m_max;
};

}  // namespace tcb
