#pragma once
/// One run: build the scene's world, step it with one method, measure it,
/// and write DIR/steps.csv and DIR/run.json (docs/contract.md "Results of one
/// run"). One step (docs/architecture.md):
///
///   handler.step(world, budget)    timed: handling_ms (wall), handling_cpu_ms (thread CPU time)
///   meters: before_dynamics        oracle, latency, probe force (never timed as handling)
///   world.step(dt)                 timed: dynamics_ms
///   meters: on_step                the row of steps.csv; stability
///
/// Stability: after every step the state is checked; a non-finite position or
/// velocity, or a vertex faster than the scene's max_speed, stops the run with
/// status "unstable" (exit 1). The files are still written, with the steps
/// done so far and the reason. Files appear only complete (run_record.hpp).

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "experiments/metrics/meter.hpp"
#include "experiments/scene/scene_desc.hpp"

namespace tcb {

struct RunOptions {
  std::string method = "full";
  BudgetSpec budget;
  /// How the budget was asked for, recorded in run.json (e.g. "full/3" when a
  /// sweep derived the absolute value from full's cost); empty: budget.label().
  std::string budget_label;
  OracleSchedule oracle;
  /// When the exact overlap volume is computed (corefinement, ~30 ms per
  /// overlapping pair: far dearer than the inside sets); unset: with the oracle.
  std::optional<OracleSchedule> overlap;
  /// When a shadow full cycle measures the force error (force_reference_meter.hpp).
  OracleSchedule force_reference;
  std::optional<std::int64_t> steps;  ///< overrides the scene's step count
  std::uint64_t seed = 0;
  std::filesystem::path out_dir;
  /// The --set strings, recorded in run.json: those that change the scene
  /// under "overrides" (a method's settings are recorded resolved, under "settings").
  std::vector<std::string> overrides;
  std::vector<std::string> argv;  ///< the command line as given, recorded in run.json
  int record_every = 0;           ///< write a VTU frame and a replay frame every N steps (0: none)
  /// Replay frames also hold the tets' boxes and the grid cells they occupy
  /// (results/replay_file.hpp); needs record_every > 0.
  bool record_debug = false;
  /// Write trajectory.bin every N steps (0: none), for runs that take this
  /// one as their --reference (results/trajectory_file.hpp).
  int trajectory_every = 0;
  /// A reference run's directory: divergence from its trajectory.bin. Empty: none.
  std::filesystem::path reference_dir;
  /// Pin the run's thread (the handling thread) to this CPU before the first
  /// step; InputError when it cannot be done. Recorded in run.json "pin".
  std::optional<int> pin_cpu;
  /// Called after every step with (steps done, steps total); for progress.
  std::function<void(std::int64_t, std::int64_t)> on_step;
  /// Called once per warning about the settings (also recorded in run.json).
  std::function<void(const std::string&)> on_warning;
  /// tcbench live: called before each step's handling, outside every timed
  /// interval (moves the mouse-driven probe to where the mouse put it).
  std::function<void(World&)> before_step;
  /// tcbench live: called after each step is measured and written (the step
  /// that went unstable too); returning false ends the run there, status ok
  /// (run.json: steps < steps_requested).
  std::function<bool(const StepContext&)> after_step;
  /// Measure the machine's overshoot floor beside the run (timing_meter.hpp:
  /// one null-handler window of a wall budget <= 10 ms after every step).
  /// tcbench live turns it off: its steps are paced to real time, and the
  /// spin would eat the time the probe has.
  bool timing_floor = true;
};

struct RunOutcome {
  std::string status;  ///< "ok" or "unstable"
  std::string reason;  ///< why unstable; empty when ok
  std::int64_t steps_done = 0;
  double wall_s = 0.0;
  int exit_code() const { return status == "ok" ? 0 : 1; }
};

RunOutcome run_scene(const SceneDesc& scene, const RunOptions& options);

}  // namespace tcb
