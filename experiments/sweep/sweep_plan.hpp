#pragma once
/// A sweep file (SWEEP.toml) and the list of runs it expands to.
///
///   [sweep]
///   description = "..."                    # optional
///   scenes  = ["plates20", "cube_drop"]    # names or paths, as `tcbench run` takes them
///   methods = ["full", "interruptible", { name = "every_nth", n = 4 },
///              { name = "interruptible_tracked", budgets = ["full-work/6"] }]
///                                          # registry names, or a table with the method's
///                                          # settings under their [method.NAME] names
///                                          # (--set method.every_nth.n=4 for that run)
///   budgets = ["none", "ms:4.5", "work:20000", "full/3", "full-work/3"]
///   seeds   = [0]                          # optional, default [0]; repeats of every run: a seed
///                                          # changes a run only through [perturb] jitter (e.g.
///                                          # sets = [["perturb.velocity=1e-3"]])
///   quick_seeds = 2                        # optional: under `reproduce --quick`, only the first N seeds
///   steps   = 200                          # optional: every run's length
///   quick_steps = 300                      # optional: the length under `reproduce --quick`
///   record  = 40                           # optional: VTU frames every N steps (report animation)
///   oracle  = "every:10"                   # optional, default "off"
///   oracle_volume = "off"                  # optional, default: with the oracle
///   force_reference = "every:10"           # optional, default "off": force error against full
///   divergence = 10                        # optional: the full reference run records its state
///                                          # every 10 steps (--trajectory), every other run of
///                                          # its group is compared with it (--reference), and a
///                                          # noise-floor run (full under [perturb] position =
///                                          # noise_floor) joins each group
///   noise_floor = 1e-9                     # optional, m, default 1e-9 (0: no noise-floor run)
///   sets    = [[], ["scene.dt=0.002"]]     # optional variants of --set, default [[]]
///   figures = ["jitter", "animation"]      # optional: the report's figures these runs feed
///                                          # (report/tcbench_report/figures/<name>.py; the
///                                          # generic figures take every run anyway)
///
/// Budgets: "none"; absolute "ms:X" (wall clock) or "work:N" (work units), as
/// BudgetSpec (method/handler/budget.hpp) parses them;
/// relative to the scene's full handling cost, measured in the same sweep by a
/// reference run (method full, budget none, same scene, seed and set):
/// "full/K" is full's median handling_ms divided by K, "full-work/K" its mean
/// work units per step divided by K (same on every machine). Methods that
/// ignore budgets (registry: uses_budget false) run once, with budget none.
///
/// Runs are grouped by (scene, set, seed); a group holds its reference run,
/// so `--shard I/N` hands out whole groups (group index mod N == I, 0-based)
/// and every run lands in exactly one shard.

#include <filesystem>

#include "method/handler/budget.hpp"
#include <optional>
#include <string>
#include <vector>

namespace tcb {

/// A sweep's budget: an absolute BudgetSpec, or one relative to the
/// reference run's cost, which only the sweep runner can resolve.
struct SweepBudget {
  enum class Relative { No, FullMs, FullWork } relative = Relative::No;
  BudgetSpec absolute;   ///< when not relative
  double divisor = 1.0;  ///< K of full/K or full-work/K
  std::string label = "none";  ///< as written: "none", "ms:4.5", "full/3", ...
  bool is_relative() const { return relative != Relative::No; }
};

/// Parses one budget label; std::nullopt when malformed.
std::optional<SweepBudget> parse_sweep_budget(const std::string& label);

struct SweepRun {
  std::string id;  ///< unique, usable as a directory name
  std::string scene, method;
  std::vector<std::string> method_sets;  ///< the method's settings as --set method.NAME.KEY=VALUE
  SweepBudget budget;
  std::uint64_t seed = 0;
  std::size_t set_index = 0;
  std::vector<std::string> sets;  ///< the scene variant's --set strings
  std::size_t group = 0;        ///< index of its (scene, set, seed) group
  std::size_t seed_index = 0;   ///< position of its seed in the plan's seeds
  /// The group's full run (method full, budget none): the cost relative
  /// budgets divide, and with `divergence` the run compared with.
  std::string reference_id;
};

struct SweepPlan {
  std::filesystem::path file;
  std::string description;
  std::optional<std::int64_t> steps, quick_steps;
  std::vector<std::uint64_t> seeds{0};
  std::optional<std::size_t> quick_seeds;  ///< under --quick, the first N seeds only
  int record = 0;  ///< --record N for every run (0: none)
  std::string oracle = "off";
  std::optional<std::string> oracle_volume;
  std::string force_reference = "off";
  int divergence_every = 0;     ///< 0: no trajectories, no divergence
  double noise_floor_m = 1e-9;  ///< the noise-floor run's [perturb] position (0: none)
  std::vector<std::string> figures;  ///< the report figures the runs feed
  std::vector<SweepRun> runs;  ///< references before the runs that need them
  std::size_t groups = 0;
};

/// Reads and expands a sweep file; InputError (file:line) for anything wrong,
/// including unknown scenes and methods, before any run starts.
SweepPlan load_sweep_plan(const std::filesystem::path& path);

/// The same from text; `path` names the file in errors and anchors relative paths.
SweepPlan parse_sweep_plan(std::string_view text, const std::filesystem::path& path);

/// The plan `reproduce --quick` runs: the runs of the first quick_seeds
/// seeds (all when the plan sets none).
SweepPlan quick_plan(SweepPlan plan);

/// The runs of shard `index` of `count` (whole groups, index in [0, count)).
std::vector<SweepRun> shard_runs(const SweepPlan& plan, std::size_t index, std::size_t count);

/// Parses "I/N" with 0 <= I < N; InputError naming --shard otherwise.
std::pair<std::size_t, std::size_t> parse_shard(const std::string& text);

}  // namespace tcb
