// tcbench check THRESHOLDS.toml DIR: bounds on run summaries, for CI.
#include <filesystem>
#include <iostream>

#include "experiments/check/thresholds.hpp"
#include "sim/io/input_error.hpp"
#include "experiments/cli/command.hpp"

namespace tcb::cli {
namespace {

class CheckCommand final : public Command {
 public:
  explicit CheckCommand(CLI::App& parent) {
    app = parent.add_subcommand("check", "Check run summaries in a results directory against thresholds");
    app->footer(
        "Each [[threshold]] names a run (scene, method, budget label, optional seed), a summary metric\n"
        "(dotted for nested keys: handling_ms.p99, depth_err.max) and min and/or max; optional response\n"
        "(implicit or explicit) and relative_to (a method label: the bound is on the ratio to that method's\n"
        "run with budget none, same scene, seed and response). A missing run, metric or reference fails.\n"
        "A wall-clock threshold (wall budget, or a handling_ms/overshoot_pct/dynamics_ms metric) on a run\n"
        "whose summary.timing.verdict is noisy is inconclusive, neither pass nor fail.\n"
        "Exit status: 0 all pass; 1 some fail or missing (or inconclusive, with --strict-timing);\n"
        "2 malformed thresholds file; 4 the others pass but some are inconclusive (a noisy machine).\n"
        "Example: experiments/thresholds/ci.toml (work-unit budgets: the same verdict on every machine).");
    app->add_option("THRESHOLDS", m_file, "The thresholds file (.toml)")->required();
    app->add_option("DIR", m_dir, "A results directory (a sweep's --out, or runs beneath it)")->required();
    app->add_flag("--strict-timing", m_strict_timing, "Treat inconclusive (noisy-machine) checks as failures");
  }

  int execute() override {
    const std::vector<Threshold> thresholds = load_thresholds(m_file);  // the rows point into it
    // A results directory that is not there is bad input, not a failed check.
    if (!std::filesystem::is_directory(m_dir))
      throw InputError(m_dir, 0, std::filesystem::exists(m_dir) ? "is not a directory" : "no such results directory");
    const std::vector<CheckRow> rows = check_thresholds(thresholds, m_dir);
    std::cout << format_check_rows(rows, m_file);
    return check_exit_status(rows, m_strict_timing);
  }

 private:
  std::string m_file, m_dir;
  bool m_strict_timing = false;
};

}  // namespace

std::unique_ptr<Command> make_check_command(CLI::App& parent) { return std::make_unique<CheckCommand>(parent); }

}  // namespace tcb::cli
