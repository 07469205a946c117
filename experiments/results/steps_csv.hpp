#pragma once
/// steps.csv: one row per simulation step, the columns of CONTRACT.md plus
/// tcbench's own (triangle_pairs, dynamics_ms, max_speed, solver_iterations,
/// and probe_force_x/y/z: the contact force on the driven objects, N). A value that was
/// not measured this step (no handler, oracle off) is an empty cell, never 0.
/// Written to steps.csv.tmp as the run goes and renamed by commit(), so an
/// interrupted run never leaves a steps.csv that looks complete.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "sim/io/atomic_file.hpp"

namespace tcb {

struct StepRow {
  std::int64_t step = 0;
  double time_s = 0.0;
  std::optional<double> handling_ms, budget_ms;
  std::optional<std::int64_t> work_units, cycle, cycle_done, colliding_points, exact_forces, estimated_forces;
  std::optional<std::int64_t> oracle_points, triangle_pairs;
  std::optional<double> recall, precision, depth_err_mean, depth_err_max, max_depth, overlap_volume, oracle_ms;
  std::optional<double> probe_force_x, probe_force_y, probe_force_z;  ///< scenes with a driven object
  double kinetic_energy = 0.0;
  double dynamics_ms = 0.0;
  double max_speed = 0.0;
  std::int64_t solver_iterations = 0;
};

class StepsCsv {
 public:
  explicit StepsCsv(const std::filesystem::path& path);
  void write(const StepRow& row);
  void commit() { m_file.commit(); }
  static const std::vector<std::string>& columns();

 private:
  AtomicFile m_file;
};

}  // namespace tcb
