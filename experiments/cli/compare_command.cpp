// tcbench compare A B: what changed from A to B, with intervals and a rank
// test; with --threshold a regression check.
#include <filesystem>
#include <iostream>

#include "experiments/cli/command.hpp"
#include "experiments/compare/compare_results.hpp"
#include "sim/io/input_error.hpp"

namespace tcb::cli {
namespace {

class CompareCommand final : public Command {
 public:
  explicit CompareCommand(CLI::App& parent) {
    app = parent.add_subcommand("compare", "Compare two results directories (or runs): B - A with intervals");
    app->footer(
        "Runs are paired by configuration (scene, method and settings, budget, response, steps, overrides:\n"
        "everything but the seed); repeats (seeds) of a configuration give medians with bootstrap 95 %\n"
        "intervals (2000 resamples, fixed seed) and a Mann-Whitney U test (over repeats when each side has\n"
        "3 or more; for times with fewer, over the per-step values: optimistic, autocorrelated). When each\n"
        "side holds one configuration they are compared whatever they are (full against interruptible).\n"
        "--threshold METRIC=LIMIT: +X may rise by X, -X may fall by X, X either way; X% relative to A.\n"
        "A time breaks its limit only when the U test also says p < 0.05. A threshold no pair can judge fails.\n"
        "Exit status: 0 no threshold broken (or none given); 1 some threshold broken or unknown;\n"
        "2 bad input (a directory without runs, a malformed threshold).\n"
        "Example: tcbench compare results/before results/after --threshold handling_ms.p50=+10% \\\n"
        "           --threshold recall_mean=-0.01");
    app->add_option("A", m_a, "The baseline: a results directory or one run's directory")->required();
    app->add_option("B", m_b, "The candidate: a results directory or one run's directory")->required();
    app->add_option("--metric", m_metrics,
                    "A summary metric to compare, dotted (repeatable; default: times, work, recall, precision, "
                    "depth error, latency, tunnelling, jitter, stack height, force error, divergence)");
    app->add_option("--threshold", m_thresholds, "METRIC=LIMIT (repeatable): a regression check");
    app->add_flag("--json", m_json, "Print the comparison as JSON (schema tcbench.compare/1)");
  }

  int execute() override {
    std::vector<CompareThreshold> thresholds;
    for (const std::string& t : m_thresholds) thresholds.push_back(parse_compare_threshold(t));
    const std::vector<CollectedRun> a = runs_in(m_a), b = runs_in(m_b);
    const Comparison c = compare_runs(a, b, m_metrics, thresholds);
    if (m_json)
      std::cout << comparison_json(c, m_a, m_b).dump(2) << "\n";
    else
      std::cout << format_comparison(c, m_a, m_b);
    return c.regression() ? 1 : 0;
  }

 private:
  static std::vector<CollectedRun> runs_in(const std::string& dir) {
    if (!std::filesystem::is_directory(dir))
      throw InputError(dir, 0, std::filesystem::exists(dir) ? "is not a directory" : "no such results directory");
    std::vector<CollectedRun> runs = collect_runs(dir);
    if (runs.empty()) throw InputError(dir, 0, "holds no complete run (run.json with its steps.csv)");
    return runs;
  }

  std::string m_a, m_b;
  std::vector<std::string> m_metrics, m_thresholds;
  bool m_json = false;
};

}  // namespace

std::unique_ptr<Command> make_compare_command(CLI::App& parent) { return std::make_unique<CompareCommand>(parent); }

}  // namespace tcb::cli
