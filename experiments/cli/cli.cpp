#include "experiments/cli/cli.hpp"

#include <iostream>
#include <vector>

#include "experiments/cli/command.hpp"
#include "experiments/run/provenance.hpp"
#include "sim/io/input_error.hpp"

namespace tcb {

int run_cli(int argc, const char* const* argv) {
  CLI::App app{"tcbench: time-critical collision handling of deformable objects, measured against an exact oracle.\n"
               "Every subcommand has --help.",
               "tcbench"};
  app.set_version_flag("--version", version_line());
  app.require_subcommand(1);
  std::vector<std::unique_ptr<cli::Command>> commands;
  commands.push_back(cli::make_run_command(app));
  commands.push_back(cli::make_sweep_command(app));
  commands.push_back(cli::make_check_command(app));
  commands.push_back(cli::make_compare_command(app));
  commands.push_back(cli::make_reproduce_command(app));
  commands.push_back(cli::make_report_command(app));
  commands.push_back(cli::make_list_command(app));
  commands.push_back(cli::make_mesh_command(app));
  commands.push_back(cli::make_neural_command(app));
  commands.push_back(cli::make_view_command(app));
  commands.push_back(cli::make_live_command(app));
  // CLI11 says "A subcommand is required" for a misspelt command too: say
  // which word it did not know, and which it knows.
  if (argc < 2 || argv[1][0] != '-') {
    std::string names;
    bool known = false;
    for (const auto& command : commands) {
      if (!names.empty()) names += ", ";
      names += command->app->get_name();
      known = known || (argc >= 2 && command->app->get_name() == argv[1]);
    }
    if (!known) {
      std::cerr << "tcbench: error: "
                << (argc < 2 ? std::string("no command given") : "unknown command '" + std::string(argv[1]) + "'")
                << " (commands: " << names << "; tcbench --help)\n";
      return 2;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  for (const auto& command : commands) {
    if (!command->app->parsed()) continue;
    command->argv.assign(argv, argv + argc);
    try {
      return command->execute();
    } catch (const CLI::ParseError& e) {
      const int code = command->app->exit(e);
      return code == 0 ? 0 : 2;
    } catch (const InputError& e) {
      std::cerr << "tcbench: error: " << e.what() << '\n';
      return 2;
    } catch (const std::exception& e) {
      std::cerr << "tcbench: failed: " << e.what() << '\n';
      return 3;
    }
  }
  return 2;
}

}  // namespace tcb
