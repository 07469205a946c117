// tcbench sweep SWEEP.toml --out DIR: methods x budgets x scenes x seeds x sets.
#include <fmt/format.h>

#include <chrono>
#include <iostream>

#include "experiments/cli/command.hpp"
#include "experiments/cli/whole_number.hpp"
#include "experiments/sweep/sweep_runner.hpp"

namespace tcb::cli {
namespace {

std::string duration_text(double s) {
  if (s < 60) return fmt::format("{:.0f}s", s);
  if (s < 3600) return fmt::format("{:.0f}m{:02.0f}s", std::floor(s / 60), std::fmod(s, 60));
  return fmt::format("{:.0f}h{:02.0f}m", std::floor(s / 3600), std::fmod(s / 60, 60));
}

class SweepCommand final : public Command {
 public:
  explicit SweepCommand(CLI::App& parent) {
    app = parent.add_subcommand("sweep", "Run a sweep file: scenes x methods x budgets x seeds x --set variants");
    app->footer(
        "Each run is a child `tcbench run` writing DIR/runs/<id>/; DIR/summary.csv has one row per run.\n"
        "Budgets: none, ms:X, work:N, full/K (full's median handling_ms / K), full-work/K (full's work\n"
        "units per step / K); the sweep runs full first and records both forms in run.json.\n"
        "Exit status: 0 every run ok; 1 some run unstable or failed (the others still ran); 2 bad input.\n"
        "Cluster (Slurm job array of 8, one shared DIR):\n"
        "  #SBATCH --array=0-7\n"
        "  tcbench sweep my.toml --out DIR --shard $SLURM_ARRAY_TASK_ID/8 --resume\n"
        "GNU parallel on one machine with 4 shards:\n"
        "  parallel tcbench sweep my.toml --out DIR --shard {}/4 --resume ::: 0 1 2 3\n"
        "The last shard to finish writes the complete summary.csv (or rerun with --resume: nothing is redone).");
    app->add_option("SWEEP", m_file, "The sweep file (.toml); see experiments/sweeps/")->required();
    app->add_option("--out", m_out, "Result directory")->required();
    app->add_option("--jobs", m_options.jobs, "Runs at once (wall-clock budgets are only meaningful with 1)")
        ->check(whole_number(1, 1024))
        ->capture_default_str();
    app->add_option("--shard", m_shard, "Run only shard I of N (0-based, whole scene/seed/set groups)");
    app->add_flag("--resume", m_options.resume, "Skip runs whose run.json is complete; redo the rest");
    app->add_option("--pin", m_pin,
                    "Pin each job's handling thread to its own CPU: auto, or a list like 2,3 (at least --jobs CPUs)");
    app->add_flag("--quiet", m_quiet, "Print nothing but errors and the final line");
  }

  int execute() override {
    const SweepPlan plan = load_sweep_plan(m_file);
    if (!m_shard.empty()) std::tie(m_options.shard_index, m_options.shard_count) = parse_shard(m_shard);
    if (!m_pin.empty()) m_options.pin_cpus = parse_pin_cpus(m_pin, m_options.jobs);
    m_options.out_dir = m_out;
    m_options.executable = std::filesystem::read_symlink("/proc/self/exe");
    const auto t0 = std::chrono::steady_clock::now();
    std::size_t timed = 0;
    m_options.on_run = [&](std::size_t done, std::size_t total, const SweepRun& run, const std::string& status) {
      if (status != "skipped") ++timed;
      if (m_quiet) return;
      const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      const std::string eta =
          timed == 0 ? "" : " eta " + duration_text(elapsed / static_cast<double>(timed) * static_cast<double>(total - done));
      std::cerr << fmt::format("[{}/{}] {:<9} {}{}\n", done, total, status, run.id, done < total ? eta : "");
    };
    const SweepOutcome outcome = run_sweep(plan, m_options);
    std::cout << fmt::format("sweep {}: {} runs: {} ok, {} skipped (complete), {} unstable, {} failed -> {}\n",
                             m_file, outcome.total, outcome.ok, outcome.skipped, outcome.unstable, outcome.failed,
                             (std::filesystem::path(m_out) / "summary.csv").string());
    return outcome.exit_code();
  }

 private:
  std::string m_file, m_out, m_shard, m_pin;
  bool m_quiet = false;
  SweepOptions m_options;
};

}  // namespace

std::unique_ptr<Command> make_sweep_command(CLI::App& parent) { return std::make_unique<SweepCommand>(parent); }

}  // namespace tcb::cli
