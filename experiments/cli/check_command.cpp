// tcbench check THRESHOLDS.toml DIR: bounds on run summaries, for CI.
#include <fmt/format.h>

#include <iostream>

#include "experiments/check/thresholds.hpp"
#include "experiments/cli/command.hpp"

namespace tcb::cli {
namespace {

class CheckCommand final : public Command {
 public:
  explicit CheckCommand(CLI::App& parent) {
    app = parent.add_subcommand("check", "Check run summaries in a results directory against thresholds");
    app->footer(
        "Each [[threshold]] names a run (scene, method, budget label, optional seed), a summary metric\n"
        "(dotted for nested keys: handling_ms.p99, depth_err.max) and min and/or max. A missing run or\n"
        "metric fails. Exit status: 0 all pass; 1 some fail; 2 malformed thresholds file.\n"
        "Example: experiments/thresholds/ci.toml (work-unit budgets: the same verdict on every machine).");
    app->add_option("THRESHOLDS", m_file, "The thresholds file (.toml)")->required();
    app->add_option("DIR", m_dir, "A results directory (a sweep's --out, or runs beneath it)")->required();
  }

  int execute() override {
    const std::vector<Threshold> thresholds = load_thresholds(m_file);
    const std::vector<CheckRow> rows = check_thresholds(thresholds, m_dir);
    std::cout << fmt::format("{:<14} {:<16} {:<14} {:<22} {:>12} {:>22}  {}\n", "scene", "method", "budget", "metric",
                             "value", "bound", "verdict");
    int failed = 0;
    for (const CheckRow& r : rows) {
      const Threshold& t = *r.threshold;
      const std::string bound = t.min && t.max ? fmt::format("[{:.4g}, {:.4g}]", *t.min, *t.max)
                                : t.min       ? fmt::format(">= {:.4g}", *t.min)
                                              : fmt::format("<= {:.4g}", *t.max);
      std::cout << fmt::format("{:<14} {:<16} {:<14} {:<22} {:>12} {:>22}  {}\n", t.scene, t.method, t.budget, t.metric,
                               r.value ? fmt::format("{:.6g}", *r.value) : "-", bound, r.verdict);
      failed += r.verdict != "pass";
    }
    std::cout << fmt::format("{} of {} checks passed ({})\n", rows.size() - failed, rows.size(), m_file);
    return failed == 0 ? 0 : 1;
  }

 private:
  std::string m_file, m_dir;
};

}  // namespace

std::unique_ptr<Command> make_check_command(CLI::App& parent) { return std::make_unique<CheckCommand>(parent); }

}  // namespace tcb::cli
