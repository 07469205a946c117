// tcbench run SCENE: one scene, one method, results in one directory.
#include <fmt/format.h>

#include <charconv>
#include <iostream>

#include "experiments/cli/command.hpp"
#include "experiments/cli/option_checks.hpp"
#include "experiments/cli/progress_line.hpp"
#include "experiments/run/run_scene.hpp"
#include "experiments/scene/scene_file.hpp"
#include "sim/io/input_error.hpp"

namespace tcb::cli {
namespace {

// A seed as typed: digits only, within 64 bits (no sign, no wrap-around).
std::uint64_t parse_seed(const std::string& text) {
  std::uint64_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos || error != std::errc() ||
      end != text.data() + text.size())
    throw InputError("--seed", 0, "'" + text + "' is not a whole number from 0 to 18446744073709551615");
  return value;
}

class RunCommand final : public Command {
 public:
  explicit RunCommand(CLI::App& parent) {
    app = parent.add_subcommand("run", "Run one scene with one collision handling method");
    app->footer(
        "Writes DIR/steps.csv (one row per step) and DIR/run.json (settings, build, machine, summary).\n"
        "Exit status: 0 ok; 1 the run went unstable (files kept, status recorded); 2 bad input.\n"
        "Example: tcbench run cube_drop --set scene.steps=500 --set object.cube.material.youngs_modulus=2e5");
    app->add_option("SCENE", m_scene, "A scene name (tcbench list scenes) or a path to a .toml scene file")
        ->required();
    app->add_option("--method", m_options.method, "Collision handling method (tcbench list methods)")
        ->capture_default_str();
    auto* wall = app->add_option("--budget-ms", m_budget_ms,
                                 "Wall-clock budget per step for collision handling (ms, a plain decimal >= 0), "
                                 "polled at interruption points");
    auto* work = app->add_option("--budget-work", m_budget_work,
                                 "Budget per step in work units (a whole number, 0 .. 2^53; bit-identical on every "
                                 "machine)");
    wall->excludes(work);
    app->add_option("--oracle", m_oracle,
                    "When the exact oracle runs: off, every, or every:K (its time is oracle_ms, never handling)")
        ->capture_default_str();
    app->add_option("--oracle-volume", m_overlap,
                    "When the exact overlap volume is computed: off, every or every:K (default: with --oracle; "
                    "corefinement costs ~30 ms per overlapping pair)");
    app->add_option("--force-reference", m_force_reference,
                    "When a shadow full cycle measures the force error: off, every or every:K (its time is "
                    "reference_ms, never handling)")
        ->capture_default_str();
    app->add_option("--budget-label", m_options.budget_label,
                    "How the budget was asked for, recorded in run.json (sweeps pass e.g. full/3)");
    app->add_option("--steps", m_steps, "Number of steps (default: the scene's)")->transform(whole_number(0, std::int64_t{1} << 40));
    app->add_option("--seed", m_seed, "Seed (a whole number, 0 .. 2^64-1): draws the scene's [perturb] offsets")
        ->capture_default_str();
    app->add_option("--set", m_options.overrides,
                    "Override a scene key, e.g. scene.dt=0.002, or a method setting, e.g. method.every_nth.n=4 "
                    "(repeatable; `tcbench list methods` lists the settings)");
    app->add_option("--record", m_options.record_every,
                    "Write a ParaView frame (DIR/frames/*.vtu, DIR/frames.pvd) and a replay frame (DIR/replay.bin, "
                    "DIR/replay.json) every N steps")
        ->transform(whole_number(1, std::int64_t{1} << 30));
    app->add_flag("--record-debug", m_options.record_debug,
                  "With --record: replay frames also hold every tet's box and the hash grid cells they occupy");
    app->add_option("--trajectory", m_options.trajectory_every,
                    "Write every body's state to DIR/trajectory.bin every N steps (float32), for runs that "
                    "take this one as --reference")
        ->transform(whole_number(1, std::int64_t{1} << 30));
    app->add_option("--reference", m_options.reference_dir,
                    "A reference run's directory (made with --trajectory): divergence from it, per recorded step "
                    "(summary: divergence)");
    app->add_option("--out", m_out, "Result directory (default: results/runs/SCENE-METHOD)")->check(non_empty_path());
    app->add_option("--pin", m_pin,
                    "Pin the handling thread to this CPU (recorded in run.json; exit 2 when not allowed here)")
        ->transform(whole_number(0, 4095));
    app->add_option("--threads", m_threads,
                    "Threads for the collision cycle's tet and surface hashing, point queries, border depths and "
                    "forces (the scene's collision.threads; default 1, "
                    "which keeps wall-clock budgets on one core; the results are the same for every count; "
                    "above 1, run.json records the cores' handover ratio, which the times depend on)")
        ->transform(whole_number(1, 64));
    app->add_flag("--quiet", m_quiet, "Print nothing but errors");
  }

  int execute() override {
    if (m_options.record_debug && m_options.record_every <= 0)
      throw InputError("--record-debug", 0, "needs --record N (the debug buffers go into the replay's frames)");
    const auto path = resolve_scene(m_scene, default_scene_dirs());
    if (m_threads > 0) m_options.overrides.push_back("collision.threads=" + std::to_string(m_threads));
    const SceneDesc scene = load_scene_file(path, m_options.overrides);
    if (m_steps >= 0) m_options.steps = m_steps;
    if (m_pin >= 0) m_options.pin_cpu = m_pin;
    m_options.oracle = parse_oracle_schedule(m_oracle);
    m_options.force_reference = parse_oracle_schedule(m_force_reference, "--force-reference");
    if (app->count("--oracle-volume")) m_options.overlap = parse_oracle_schedule(m_overlap, "--oracle-volume");
    // Parsed here, as text, so nothing is silently rewritten: CLI11 would turn
    // -5 or 2^64-1 into work:0 and accept "nan" milliseconds.
    if (app->count("--budget-ms")) {
      const auto spec = BudgetSpec::parse("ms:" + m_budget_ms);
      if (!spec) throw InputError("--budget-ms", 0, "'" + m_budget_ms + "' is not a plain decimal number of milliseconds >= 0 (e.g. 4.5)");
      m_options.budget = *spec;
    }
    if (app->count("--budget-work")) {
      const auto spec = BudgetSpec::parse("work:" + m_budget_work);
      if (!spec)
        throw InputError("--budget-work", 0,
                         "'" + m_budget_work + "' is not a whole number of work units from 0 to 9007199254740992 (2^53)");
      m_options.budget = *spec;
    }
    m_options.seed = parse_seed(m_seed);
    m_options.out_dir = m_out.empty() ? std::filesystem::path("results/runs") / (scene.name + "-" + m_options.method)
                                      : std::filesystem::path(m_out);
    // The run replaces the files of an earlier run in its directory, the
    // reference's trajectory among them.
    if (!m_options.reference_dir.empty() && std::filesystem::exists(m_options.out_dir) &&
        std::filesystem::exists(m_options.reference_dir) &&
        std::filesystem::equivalent(m_options.reference_dir, m_options.out_dir))
      throw InputError("--reference", 0, "is the --out directory, whose files this run replaces; write the run elsewhere");
    m_options.argv = argv;
    ProgressLine progress(fmt::format("{} [{}]", scene.name, m_options.method), !m_quiet && stderr_is_terminal());
    m_options.on_step = [&](std::int64_t done, std::int64_t total) { progress.update(done, total); };
    m_options.on_warning = [](const std::string& w) { std::cerr << "tcbench: warning: " << w << '\n'; };
    const RunOutcome outcome = run_scene(scene, m_options);
    progress.finish();
    if (outcome.status != "ok") {
      std::cerr << fmt::format("tcbench: run unstable: {}; {} steps written to {}\n", outcome.reason,
                               outcome.steps_done, m_options.out_dir.string());
    } else if (!m_quiet) {
      std::cout << fmt::format("{} [{}]: ok, {} steps in {:.2f} s -> {}\n", scene.name, m_options.method,
                               outcome.steps_done, outcome.wall_s, m_options.out_dir.string());
    }
    return outcome.exit_code();
  }

 private:
  std::string m_scene, m_out;
  std::int64_t m_steps = -1;
  int m_pin = -1;
  int m_threads = 0;  // 0: the scene's collision.threads
  std::string m_oracle = "off", m_overlap, m_force_reference = "off";
  std::string m_budget_ms, m_budget_work, m_seed = "0";
  bool m_quiet = false;
  RunOptions m_options;
};

}  // namespace

std::unique_ptr<Command> make_run_command(CLI::App& parent) { return std::make_unique<RunCommand>(parent); }

}  // namespace tcb::cli
