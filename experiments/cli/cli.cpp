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
  // Help and version as CLI11 prints them; a usage error as every other bad
  // input is said: one line, with where to read more.
  const auto parse_failure = [&](const CLI::ParseError& e) {
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);
    std::string help = "tcbench";  // the chain of (sub)commands parsed when it failed: "tcbench mesh info"
    for (const CLI::App* at = &app;;) {
      const std::vector<CLI::App*> subs = at->get_subcommands();
      if (subs.empty()) break;
      at = subs.front();
      help += " " + at->get_name();
    }
    help += " --help";
    std::cerr << "tcbench: error: " << e.what() << " (" << help << ")\n";
    return 2;
  };
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return parse_failure(e);
  }
  for (const auto& command : commands) {
    if (!command->app->parsed()) continue;
    command->argv.assign(argv, argv + argc);
    try {
      return command->execute();
    } catch (const CLI::ParseError& e) {
      return parse_failure(e);
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
