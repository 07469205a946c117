#pragma once
// One subcommand of tcbench: registers its options on a CLI11 sub-app, and
// executes once parsing chose it.

#include <CLI/CLI.hpp>

#include <memory>
#include <string>
#include <vector>

namespace tcb::cli {

class Command {
 public:
  virtual ~Command() = default;
  virtual int execute() = 0;
  CLI::App* app = nullptr;
  /// The whole command line as given (recorded by the commands that write results).
  std::vector<std::string> argv;
};

std::unique_ptr<Command> make_run_command(CLI::App& parent);
std::unique_ptr<Command> make_list_command(CLI::App& parent);
std::unique_ptr<Command> make_mesh_command(CLI::App& parent);
std::unique_ptr<Command> make_reproduce_command(CLI::App& parent);
std::unique_ptr<Command> make_sweep_command(CLI::App& parent);
std::unique_ptr<Command> make_check_command(CLI::App& parent);
std::unique_ptr<Command> make_compare_command(CLI::App& parent);
std::unique_ptr<Command> make_report_command(CLI::App& parent);
std::unique_ptr<Command> make_neural_command(CLI::App& parent);
std::unique_ptr<Command> make_view_command(CLI::App& parent);
std::unique_ptr<Command> make_live_command(CLI::App& parent);

}  // namespace tcb::cli
