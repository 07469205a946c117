// tcbench sweep SWEEP.toml --out DIR: methods x budgets x scenes x seeds x sets.
#include <fmt/format.h>

#include <chrono>
#include <iostream>

#include "experiments/cli/command.hpp"
#include "experiments/cli/option_checks.hpp"
#include "experiments/run/provenance.hpp"
#include "experiments/sweep/slurm_script.hpp"
#include "experiments/sweep/sweep_runner.hpp"
#include "sim/io/atomic_file.hpp"
#include "sim/io/input_error.hpp"

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
        "Cluster (Slurm job array of 8 shards, one shared DIR):\n"
        "  tcbench sweep my.toml --out DIR --slurm 8     # writes DIR/sweep.sbatch, runs nothing\n"
        "  sbatch DIR/sweep.sbatch                        # resubmit shard I alone: sbatch --array=I DIR/sweep.sbatch\n"
        "  (each array task: tcbench sweep my.toml --out DIR --shard $SLURM_ARRAY_TASK_ID/8 --resume)\n"
        "GNU parallel on one machine with 4 shards:\n"
        "  parallel tcbench sweep my.toml --out DIR --shard {}/4 --resume ::: 0 1 2 3\n"
        "The last shard to finish writes the complete summary.csv (or rerun with --resume: nothing is redone).");
    app->add_option("SWEEP", m_file, "The sweep file (.toml); see experiments/sweeps/")->required();
    app->add_option("--out", m_out, "Result directory")->check(non_empty_path())->required();
    app->add_option("--jobs", m_options.jobs, "Runs at once (wall-clock budgets are only meaningful with 1)")
        ->transform(whole_number(1, 1024))
        ->capture_default_str();
    app->add_option("--shard", m_shard, "Run only shard I of N (0-based, whole scene/seed/set groups)");
    app->add_option("--slurm", m_slurm_shards,
                    "Write DIR/sweep.sbatch, a Slurm job array of N shards (each --resume, --jobs CPUs), and run nothing")
        ->transform(whole_number(1, 100000));
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
    if (m_slurm_shards > 0) return write_slurm_script(plan);
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
  int write_slurm_script(const SweepPlan& plan) {
    if (!m_shard.empty()) throw InputError("--slurm", 0, "cannot be combined with --shard (the script shards the sweep)");
    namespace fs = std::filesystem;
    SlurmArraySettings settings;
    settings.executable = m_options.executable;
    settings.sweep_file = fs::absolute(m_file).lexically_normal();
    settings.out_dir = fs::absolute(m_out).lexically_normal();
    settings.shards = m_slurm_shards;
    settings.jobs = m_options.jobs;
    settings.pin = m_pin;
    settings.job_name = "tcbench-" + settings.sweep_file.stem().string();
    settings.provenance = "Written by `tcbench sweep --slurm " + std::to_string(m_slurm_shards) + "` (" + version_line() +
                          ") at " + utc_timestamp() + " for " + std::to_string(plan.runs.size()) + " runs.";
    fs::create_directories(settings.out_dir / "slurm");  // sbatch does not create the folder of --output
    const fs::path script = settings.out_dir / "sweep.sbatch";
    write_file_atomically(script, slurm_array_script(settings));
    fs::permissions(script, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec, fs::perm_options::add);
    std::cout << fmt::format("wrote {}: {} runs as a Slurm array of {} shards, {} CPU(s) each\n"
                             "submit:   sbatch {}\n"
                             "resubmit shard I (cancelled, failed, timed out): sbatch --array=I {}\n",
                             script.string(), plan.runs.size(), m_slurm_shards, m_options.jobs, script.string(),
                             script.string());
    return 0;
  }

  std::string m_file, m_out, m_shard, m_pin;
  std::size_t m_slurm_shards = 0;
  bool m_quiet = false;
  SweepOptions m_options;
};

}  // namespace

std::unique_ptr<Command> make_sweep_command(CLI::App& parent) { return std::make_unique<SweepCommand>(parent); }

}  // namespace tcb::cli
