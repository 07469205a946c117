// tcbench reproduce [--quick] [--out DIR]: the paper's experiment set.
//
// What exists today: the scenes, the collision pipeline and the baselines
// (full, every_nth), but not the interruptible method, the oracle or the
// report. reproduce runs the baselines on the scenes and says plainly, on the
// terminal and in DIR/summary.md, that no figure of the paper is reproduced.
#include <fmt/format.h>

#include <iostream>

#include "experiments/cli/command.hpp"
#include "experiments/cli/progress_line.hpp"
#include "experiments/run/provenance.hpp"
#include "experiments/run/run_scene.hpp"
#include "experiments/scene/scene_file.hpp"
#include <nlohmann/json.hpp>

#include "sim/io/atomic_file.hpp"

namespace tcb::cli {
namespace {

constexpr std::int64_t kQuickSteps = 200;

class ReproduceCommand final : public Command {
 public:
  explicit ReproduceCommand(CLI::App& parent) {
    app = parent.add_subcommand("reproduce", "Run the paper's experiment set and write a summary");
    app->footer("Today this runs the baselines (full, every_nth) on the scenes that exist and reproduces no\n"
                "figure of the paper (the interruptible method, the oracle and the report are not built yet);\n"
                "DIR/summary.md says which ones are missing.");
    app->add_flag("--quick", m_quick, fmt::format("Run each scene for at most {} steps", kQuickSteps));
    app->add_option("--out", m_out, "Result directory")->capture_default_str();
  }

  int execute() override {
    const std::vector<std::pair<std::string, std::string>> runs = {
        {"cube_drop", "full"}, {"plates20", "full"}, {"plates20", "every_nth"}};
    std::cout << "tcbench reproduce: the interruptible method, the oracle and the report are not built yet, so this\n"
                 "runs the baselines only and reproduces no figure of the paper.\n";
    std::string table =
        "| scene | method | steps | status | wall s | handling ms p50 | handling ms max |\n|---|---|---|---|---|---|---|\n";
    int exit_code = 0;
    for (const auto& [name, method] : runs) {
      const SceneDesc scene = load_scene_file(resolve_scene(name, default_scene_dirs()));
      RunOptions options;
      options.method = method;
      options.out_dir = std::filesystem::path(m_out) / "runs" / (name + "-" + method);
      if (m_quick) options.steps = std::min<std::int64_t>(scene.steps, kQuickSteps);
      options.command_line = "tcbench reproduce" + std::string(m_quick ? " --quick" : "");
      ProgressLine progress(fmt::format("{} [{}]", name, method), stderr_is_terminal());
      options.on_step = [&](std::int64_t done, std::int64_t total) { progress.update(done, total); };
      const RunOutcome outcome = run_scene(scene, options);
      progress.finish();
      std::cout << fmt::format("  {:<12} {:<10} {} ({} steps, {:.2f} s)\n", name, method, outcome.status,
                               outcome.steps_done, outcome.wall_s);
      const auto run = nlohmann::json::parse(read_file(options.out_dir / "run.json"));
      const auto& handling = run["summary"]["handling_ms"];
      table += fmt::format("| {} | {} | {} | {} | {:.2f} | {} | {} |\n", name, method, outcome.steps_done,
                           outcome.status, outcome.wall_s, handling.is_null() ? "-" : fmt::format("{:.3g}", handling["p50"].get<double>()),
                           handling.is_null() ? "-" : fmt::format("{:.3g}", handling["max"].get<double>()));
      exit_code = std::max(exit_code, outcome.exit_code());
    }
    const std::string summary = fmt::format(
        "# tcbench reproduce\n\n"
        "Built by {} on {} ({} cores), {}.\n\n"
        "## What ran\n\n{}\n"
        "## What is not reproduced yet\n\n"
        "None of the paper's figures or claims: handling time with and without interruption (plates20,\n"
        "sneaker_grass), budget granularity, speed-up, jitter of the stack, latency and tunnelling\n"
        "(fast_sphere_torus), the haptic force signal and the claims table need the interruptible handler,\n"
        "the oracle, the remaining scenes and the report, which are not built yet.\n",
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
