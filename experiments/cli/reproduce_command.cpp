// tcbench reproduce [--quick] [--out DIR]: the paper's experiment set.
//
// What exists today: the dynamics of the scenes, without collision handling
// (no handler is implemented yet). reproduce runs those scenes and says
// plainly, on the terminal and in DIR/summary.md, that no figure of the paper
// is reproduced by it.
#include <fmt/format.h>

#include <iostream>

#include "experiments/cli/command.hpp"
#include "experiments/cli/progress_line.hpp"
#include "experiments/run/provenance.hpp"
#include "experiments/run/run_scene.hpp"
#include "experiments/scene/scene_file.hpp"
#include "sim/io/atomic_file.hpp"

namespace tcb::cli {
namespace {

constexpr std::int64_t kQuickSteps = 200;

class ReproduceCommand final : public Command {
 public:
  explicit ReproduceCommand(CLI::App& parent) {
    app = parent.add_subcommand("reproduce", "Run the paper's experiment set and write a summary");
    app->footer("Today this runs the scenes that exist with method 'none' (no collision handler is implemented\n"
                "yet) and reproduces no figure of the paper; DIR/summary.md says which ones are missing.");
    app->add_flag("--quick", m_quick, fmt::format("Run each scene for at most {} steps", kQuickSteps));
    app->add_option("--out", m_out, "Result directory")->capture_default_str();
  }

  int execute() override {
    const std::vector<std::string> scenes = {"cube_drop", "plates20"};
    std::cout << "tcbench reproduce: no collision handler exists yet, so this runs the dynamics of "
              << scenes.size() << " scenes with method 'none' and reproduces no figure of the paper.\n";
    std::string table = "| scene | method | steps | status | wall s | dynamics ms p50 |\n|---|---|---|---|---|---|\n";
    int exit_code = 0;
    for (const std::string& name : scenes) {
      const SceneDesc scene = load_scene_file(resolve_scene(name, default_scene_dirs()));
      RunOptions options;
      options.method = "none";
      options.out_dir = std::filesystem::path(m_out) / "runs" / (name + "-none");
      if (m_quick) options.steps = std::min<std::int64_t>(scene.steps, kQuickSteps);
      options.command_line = "tcbench reproduce" + std::string(m_quick ? " --quick" : "");
      ProgressLine progress(fmt::format("{} [none]", name), stderr_is_terminal());
      options.on_step = [&](std::int64_t done, std::int64_t total) { progress.update(done, total); };
      const RunOutcome outcome = run_scene(scene, options);
      progress.finish();
      std::cout << fmt::format("  {:<12} {} ({} steps, {:.2f} s)\n", name, outcome.status, outcome.steps_done,
                               outcome.wall_s);
      table += fmt::format("| {} | none | {} | {} | {:.2f} | see runs/{}-none/run.json |\n", name,
                           outcome.steps_done, outcome.status, outcome.wall_s, name);
      exit_code = std::max(exit_code, outcome.exit_code());
    }
    const std::string summary = fmt::format(
        "# tcbench reproduce\n\n"
        "Built by {} on {} ({} cores), {}.\n\n"
        "## What ran\n\n{}\n"
        "## What is not reproduced yet\n\n"
        "No collision handler is implemented yet, so none of the paper's figures or claims is reproduced:\n"
        "handling time with and without interruption (plates20, sneaker_grass), budget granularity,\n"
        "speed-up, jitter of the stack, latency and tunnelling (fast_sphere_torus), the haptic force signal,\n"
        "and the claims table all need the collision pipeline, the interruptible handler and the oracle.\n",
        version_line(), machine_info()["cpu"].get<std::string>(), machine_info()["cores"].get<unsigned>(),
        utc_timestamp(), table);
    write_file_atomically(std::filesystem::path(m_out) / "summary.md", summary);
    std::cout << "summary: " << (std::filesystem::path(m_out) / "summary.md").string() << '\n';
    return exit_code;
  }

 private:
  bool m_quick = false;
  std::string m_out = "results/reproduce";
};

}  // namespace

std::unique_ptr<Command> make_reproduce_command(CLI::App& parent) {
  return std::make_unique<ReproduceCommand>(parent);
}

}  // namespace tcb::cli
