// tcbench reproduce [--quick] [--out DIR]: the paper's experiment set, then
// the report. The set is the sweep files in experiments/sweeps/paper/, run one
// after the other with one job (wall-clock budgets need a quiet machine), each
// into DIR/<sweep name>/; then the neural experiment into DIR/7_neural; then the viewer's screenshot of
// the stack (DIR/viewer/); then `tcbench report DIR`; then, for full-length
// runs, `tcbench check experiments/thresholds/paper.toml DIR` (also written to
// DIR/check.txt): the claims the project holds itself to at the paper's
// lengths. --quick runs are too short for them and are not checked.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <thread>
#include <iostream>

#include "experiments/check/thresholds.hpp"
#include "experiments/run/thread_clock.hpp"
#include "experiments/cli/command.hpp"
#include "experiments/cli/option_checks.hpp"
#include "experiments/cli/report_runner.hpp"
#include "experiments/cli/screenshot_runner.hpp"
#include "experiments/neural/neural_experiment.hpp"
#include "experiments/run/provenance.hpp"
#include "experiments/sweep/sweep_runner.hpp"
#include "sim/io/atomic_file.hpp"
#include "sim/io/input_error.hpp"


namespace tcb::cli {
namespace {

class ReproduceCommand final : public Command {
 public:
  explicit ReproduceCommand(CLI::App& parent) {
    app = parent.add_subcommand("reproduce", "Run the paper's experiment set and draw the report");
    app->footer(
        "Runs every sweep in experiments/sweeps/paper/ (about two hours on 2 cores, most of it the stack: both\n"
        "response modes and five jittered seeds; --quick: shorter runs, fewer seeds, about 20 min), then\n"
        "the neural detector's experiment (`tcbench neural experiment`, into DIR/7_neural), then the viewer's\n"
        "screenshot of the stack (full beside interruptible, DIR/viewer/; said and skipped without a browser), then\n"
        "`tcbench report DIR` (DIR/report/index.html), then (not with --quick) checks\n"
        "experiments/thresholds/paper.toml against the runs (DIR/check.txt).\n"
        "Exit status: 0 all runs ok and all checks pass; 1 some run unstable or failed, or a check failed (the\n"
        "report still shows it); 2 bad input.");
    app->add_flag("--quick", m_options.quick, "Shortened runs (each sweep's quick_steps)");
    app->add_flag("--resume", m_options.resume, "Keep complete runs of an earlier reproduce in DIR");
    app->add_option("--out", m_out, "Result directory")->check(non_empty_path())->capture_default_str();
    app->add_option("--pin", m_pin, "The CPU the runs are pinned to, or auto (the highest this process may use)")
        ->capture_default_str();
  }

  int execute() override {
    const auto dir = source_tree_dir() / "experiments" / "sweeps" / "paper";
    const auto thresholds_file = source_tree_dir() / "experiments" / "thresholds" / "paper.toml";
    const std::vector<Threshold> thresholds = load_thresholds(thresholds_file);  // checked before anything runs
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::directory_iterator(dir))
      if (entry.path().extension() == ".toml") files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    std::vector<SweepPlan> plans;
    std::size_t total = 0;
    for (const auto& f : files) {
      plans.push_back(load_sweep_plan(f));  // all checked before anything runs
      if (m_options.quick && plans.back().quick_seeds && *plans.back().quick_seeds < plans.back().seeds.size()) {
        std::cerr << fmt::format("reproduce --quick: {} runs the first {} of its {} seeds\n", f.filename().string(),
                                 *plans.back().quick_seeds, plans.back().seeds.size());
        plans.back() = quick_plan(std::move(plans.back()));
      }
      total += plans.back().runs.size();
    }
    m_options.executable = std::filesystem::read_symlink("/proc/self/exe");
    m_options.jobs = 1;
    // Pinned where the machine allows (the highest allowed CPU, away from CPU
    // 0's interrupts); said either way, and recorded in every run.json.
    try {
      m_options.pin_cpus = parse_pin_cpus(m_pin, 1);
      // The kernel may still refuse (a container's policy): try it on a
      // thread of our own before every run would fail on it.
      std::string refused;
      std::thread([&] {
        refused = pin_current_thread(m_options.pin_cpus[0]);
      }).join();
      if (!refused.empty()) throw InputError("--pin", 0, refused);
      std::cerr << fmt::format("reproduce: runs pinned to CPU {}\n", m_options.pin_cpus[0]);
    } catch (const InputError& e) {
      if (m_pin != "auto") throw;
      m_options.pin_cpus.clear();
      std::cerr << "reproduce: runs not pinned (" << e.what() << ")\n";
    }
    const auto t0 = std::chrono::steady_clock::now();
    std::size_t done = 0;
    int exit_code = 0;
    for (const SweepPlan& plan : plans) {
      m_options.out_dir = std::filesystem::path(m_out) / plan.file.stem();
      std::cerr << fmt::format("sweep {} ({}): {}\n", plan.file.stem().string(), plan.description,
                               m_options.out_dir.string());
      m_options.on_run = [&](std::size_t, std::size_t, const SweepRun& run, const std::string& status) {
        ++done;
        const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        std::cerr << fmt::format("  [{}/{}] {:<9} {} ({:.0f} s elapsed)\n", done, total, status, run.id, elapsed);
      };
      exit_code = std::max(exit_code, run_sweep(plan, m_options).exit_code());
    }
    // The neural detector of seed 002 is not a sweep of runs: its experiment
    // writes its own tables, which the report finds beneath DIR.
    // --resume keeps an earlier neural experiment only when it ran this mode's
    // seeds and presets (a --quick one is redone by a full reproduce).
    const NeuralExperimentSettings wanted = neural_experiment_defaults(m_options.quick);
    if (!(m_options.resume && neural_results_match(std::filesystem::path(m_out) / "7_neural" / "neural.json", wanted))) {
      NeuralExperimentSettings neural = wanted;
      neural.out = std::filesystem::path(m_out) / "7_neural";
      neural.jobs = 2;  // not a timing experiment: both cores
      neural.command_line = argv;
      neural.progress = [&](const std::string& line) {
        const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        std::cerr << fmt::format("  neural: {} ({:.0f} s elapsed)\n", line, elapsed);
      };
      std::cerr << fmt::format("neural experiment (seed 002): {}\n", neural.out.string());
      run_neural_experiment(neural);
    }
    // The viewer's picture of the stack for the report (not fatal when it cannot be made).
    make_viewer_screenshot(m_out, m_options.executable);
    const int report = run_report(m_out);
    if (!m_options.quick) {
      const std::vector<CheckRow> rows = check_thresholds(thresholds, m_out);
      const std::string table = format_check_rows(rows, thresholds_file.string());
      write_file_atomically(std::filesystem::path(m_out) / "check.txt", table);
      std::cout << table;
      if (check_exit_status(rows, false) == 1) exit_code = std::max(exit_code, 1);  // work budgets: never inconclusive
    }
    const double minutes = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / 60.0;
    std::cout << fmt::format("reproduce: {} runs in {:.1f} min -> {}/report/index.html\n", total, minutes, m_out);
    return report != 0 ? report : exit_code;
  }

 private:
  std::string m_out = "results/reproduce";
  std::string m_pin = "auto";
  SweepOptions m_options;
};

}  // namespace

std::unique_ptr<Command> make_reproduce_command(CLI::App& parent) {
  return std::make_unique<ReproduceCommand>(parent);
}

}  // namespace tcb::cli
