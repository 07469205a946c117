// tcbench report DIR: figures, summary.md and index.html from a results
// directory, drawn by report/make_report.py with Debian's matplotlib.
#include "experiments/cli/command.hpp"
#include "experiments/cli/report_runner.hpp"

namespace tcb::cli {
namespace {

class ReportCommand final : public Command {
 public:
  explicit ReportCommand(CLI::App& parent) {
    app = parent.add_subcommand("report", "Draw the report (figures, summary.md, index.html) from a results directory");
    app->footer(
        "Reads every complete run.json (and steps.csv) beneath DIR; writes DIR/report/. Needs /usr/bin/python3\n"
        "with matplotlib (Debian: python3-matplotlib; scripts/setup installs it). Figures without data say so.");
    app->add_option("DIR", m_dir, "A results directory (reproduce's or a sweep's --out)")->required();
  }

  int execute() override { return run_report(m_dir); }

 private:
  std::string m_dir;
};

}  // namespace

std::unique_ptr<Command> make_report_command(CLI::App& parent) { return std::make_unique<ReportCommand>(parent); }

}  // namespace tcb::cli
