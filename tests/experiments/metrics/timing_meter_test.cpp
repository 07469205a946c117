// The handling and timing meters on injected per-step wall and CPU times (the
// run loop's clocks are replaced by the numbers a StepContext carries).
#include "experiments/metrics/timing_meter.hpp"

#include <catch2/catch.hpp>

#include "baselines/registry.hpp"
#include "experiments/metrics/handling_meter.hpp"
#include "experiments/scene/scene_file.hpp"

using namespace tcb;

namespace {

SceneDesc one_cube() {
  return parse_scene(R"([scene]
dt = 0.001
steps = 4
[[object]]
name = "cube"
mesh = "box:size=0.1x0.1x0.1,cells=1x1x1"
)",
                     "cube.toml");
}

struct Step {
  double wall_ms, cpu_ms;
  std::int64_t switches;
};

nlohmann::ordered_json measure(const BudgetSpec& budget, const std::vector<Step>& steps, bool timing_floor = true) {
  const SceneDesc scene = one_cube();
  const World world = build_world(scene.world);
  RunSetup setup{scene, world, budget, {}, {}, static_cast<std::int64_t>(steps.size())};
  setup.timing_floor = timing_floor;
  HandlingMeter handling(setup);
  TimingMeter timing(setup);
  std::map<std::string, std::size_t, std::less<>> index;
  for (const ColumnSpec& c : handling.columns()) index.emplace(c.name, index.size());
  const auto handler = make_handler("none");
  const StepReport report;
  std::int64_t n = 0;
  for (const Step& s : steps) {
    StepRow row(&index);
    StepContext ctx{.step = ++n, .world = world, .handler = *handler, .report = report, .handling_ms = s.wall_ms,
                    .handling_cpu_ms = s.cpu_ms, .handling_switches = s.switches, .row = row};
    handling.on_step(ctx);
    timing.on_step(ctx);
  }
  nlohmann::ordered_json summary;
  handling.summarize(summary);
  timing.summarize(summary);
  return summary;
}

}  // namespace

TEST_CASE("a step that lost more than 1 % of the wall budget to preemption is counted", "[timing]") {
  // Budget 4 ms: 1 % is 40 us.
  const auto s = measure(BudgetSpec{BudgetKind::WallMs, 4.0},
                         {{4.10, 4.00, 1},    // 100 us lost: preempted
                          {4.03, 4.00, 0},    // 30 us: not
                          {4.00, 4.00, 0},
                          {8.00, 4.00, 3}});  // 4 ms lost: the OS's overshoot, not the method's
  CHECK(s["timing"]["preempted_steps"] == 2);
  CHECK(s["timing"]["preempted_step_share"].get<double>() == Approx(0.5));
  CHECK(s["timing"]["involuntary_switches"] == 4);
  CHECK(s["timing"]["verdict"] == "noisy");  // 50 % of steps preempted
  // The wall overshoot says 100 %; the CPU-time overshoot says the method ran 0 % over.
  CHECK(s["overshoot_pct"]["max"].get<double>() == Approx(100.0));
  CHECK(s["overshoot_cpu_pct"]["max"].get<double>() == Approx(0.0).margin(1e-12));
  CHECK(s["handling_cpu_ms"]["max"].get<double>() == Approx(4.0));
  // One null-handler window of the budget's length a step: the machine's floor.
  CHECK(s["timing"]["floor"]["windows"] == 4);
  CHECK(s["timing"]["floor"]["overshoot_us"]["p99"].get<double>() >= 0.0);
  CHECK(s["timing"]["floor"]["overshoot_pct"]["max"].get<double>() ==
        Approx(s["timing"]["floor"]["overshoot_us"]["max"].get<double>() / 40.0));  // 1 % of 4 ms is 40 us
}

TEST_CASE("no floor is spun above kFloorMaxWindowMs, or when the run turned it off", "[timing]") {
  CHECK(measure(BudgetSpec{BudgetKind::WallMs, 2.0 * kFloorMaxWindowMs}, {{1.0, 1.0, 0}})["timing"]["floor"].is_null());
  CHECK(measure(BudgetSpec{BudgetKind::WallMs, 1.0}, {{1.0, 1.0, 0}}, false)["timing"]["floor"].is_null());
  CHECK_FALSE(measure(BudgetSpec{BudgetKind::WallMs, 1.0}, {{1.0, 1.0, 0}})["timing"]["floor"].is_null());
}

TEST_CASE("without a wall budget a step's base is its own wall time; overshoot stays null", "[timing]") {
  const auto s = measure(BudgetSpec{}, {{10.0, 9.95, 0},    // 50 us of 10 ms: not (1 % = 100 us)
                                        {10.0, 9.8, 0}});  // 200 us: preempted
  CHECK(s["timing"]["preempted_steps"] == 1);
  CHECK(s["overshoot_pct"].is_null());
  CHECK(s["overshoot_cpu_pct"].is_null());
  CHECK(s["timing"]["floor"].is_null());
}
