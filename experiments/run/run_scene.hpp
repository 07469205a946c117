#pragma once
/// One run: build the scene's world, step it, write DIR/steps.csv and
/// DIR/run.json (CONTRACT.md "Results of one run").
///
/// Stability: after every step the state is checked; a non-finite position or
/// velocity, or a vertex faster than the scene's max_speed, stops the run with
/// status "unstable" (exit 1). The files are still written, with the steps
/// done so far and the reason. Files appear only complete: steps.csv is
/// streamed to a temporary name and renamed, run.json is written last.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "sim/world/scene.hpp"

namespace tcb {

/// The per-step budget handed to the handler.
struct BudgetSpec {
  enum class Kind { None, WallMs, Work } kind = Kind::None;
  double value = 0.0;  ///< milliseconds, or work units
};

/// When the oracle runs: never (every = 0), or on every k-th step.
struct OracleSchedule {
  std::int64_t every = 0;
  bool due(std::int64_t step) const { return every > 0 && step % every == 0; }
};

/// The highest centre of mass of a dynamic body along -gravity (y without
/// gravity), m; nullopt without dynamic bodies. Summary top_centre_height_m.
std::optional<double> top_centre_height_m(const World& world);

/// "none", "ms:X" or "work:N": the absolute form of a budget, as sweeps and checks name it.
std::string budget_label(const BudgetSpec& budget);

/// Parses "off", "every" or "every:K"; InputError naming `option` otherwise.
OracleSchedule parse_oracle_schedule(const std::string& text, const std::string& option = "--oracle");

struct RunOptions {
  std::string method = "full";
  BudgetSpec budget;
  /// How the budget was asked for, recorded in run.json (e.g. "full/3" when a
  /// sweep derived the absolute value from full's cost); empty: the absolute form.
  std::string budget_label;
  OracleSchedule oracle;
  /// When the exact overlap volume is computed (corefinement, ~30 ms per
  /// overlapping pair: far dearer than the inside sets); unset: with the oracle.
  std::optional<OracleSchedule> overlap;
  std::optional<std::int64_t> steps;  ///< overrides the scene's step count
  std::uint64_t seed = 0;
  std::filesystem::path out_dir;
  std::vector<std::string> overrides;  ///< the --set strings, recorded in run.json
  std::string command_line;            ///< recorded in run.json
  int record_every = 0;                ///< write a VTU frame every N steps (0: none)
  /// Called after every step with (steps done, steps total); for progress.
  std::function<void(std::int64_t, std::int64_t)> on_step;
  /// Called once per warning about the settings (also recorded in run.json).
  std::function<void(const std::string&)> on_warning;
};

struct RunOutcome {
  std::string status;  ///< "ok" or "unstable"
  std::string reason;  ///< why unstable; empty when ok
  std::int64_t steps_done = 0;
  double wall_s = 0.0;
  int exit_code() const { return status == "ok" ? 0 : 1; }
};

/// Names of the collision handling methods run_scene accepts.
std::vector<std::pair<std::string, std::string>> available_methods();

RunOutcome run_scene(const SceneDesc& scene, const RunOptions& options);

}  // namespace tcb
