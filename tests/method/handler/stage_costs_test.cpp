// Stage costs (method/handler/stage_costs.hpp): every task's work lands in
// exactly one stage, a stage's time is the time of its tasks, and the stage
// the budget stopped the cycle in is the one it resumes in.
#include "method/handler/stage_costs.hpp"

#include <catch2/catch.hpp>

#include <algorithm>

#include "baselines/registry.hpp"
#include "method/handler/cycle_handler.hpp"
#include "tests/method/test_worlds.hpp"

using namespace tcb;

namespace {

// Which reported stage the cycle's internal stage belongs to (the header's merge).
int reported(CollisionCycle::Stage s) {
  using S = CollisionCycle::Stage;
  switch (s) {
    case S::Prioritize: return static_cast<int>(CostStage::Prioritize);
    case S::HashTets:
    case S::BuildTetHash:
    case S::RefreshTets:
    case S::BuildOverflow: return static_cast<int>(CostStage::HashTets);
    case S::QueryPoints: return static_cast<int>(CostStage::QueryPoints);
    case S::HashSurface:
    case S::BuildSurfaceHash: return static_cast<int>(CostStage::HashSurface);
    case S::BorderDepth: return static_cast<int>(CostStage::BorderDepth);
    case S::Propagate:
    case S::BuildLayer: return static_cast<int>(CostStage::Propagate);
    case S::Forces: return static_cast<int>(CostStage::Forces);
    default: return -2;  // Idle and Done are never interrupted in
  }
}

}  // namespace

TEST_CASE("stage work adds up to the step's work exactly, for every cycle method", "[stages]") {
  for (const auto& [scene_name, scene] : test::collision_scenes()) {
    for (const MethodInfo& info : method_registry()) {
      const bool has_keep = std::any_of(info.settings.begin(), info.settings.end(),
                                        [](const SettingSpec& spec) { return spec.name == "keep_table"; });
      for (const bool keep : {false, true}) {
        if (keep && !has_keep) continue;
        MethodSettings settings(info.settings);
        if (keep) settings.set("keep_table", true);
        auto handler = info.make(settings);
        if (!dynamic_cast<CycleHandler*>(handler.get())) continue;
        INFO(scene_name << ", " << info.name << (keep ? " + keep_table" : ""));
        World world = build_world(scene.world);
        handler->init(world, test::settings_of(world, scene));
        for (int s = 0; s < 12; ++s) {
          Budget budget = Budget::work_units(400);
          const StepReport r = handler->step(world, budget);
          CHECK(r.stages.total_work() == r.work_units);
          CHECK(r.stages.ms_of(CostStage::Apply) >= -1e-12);
          for (double ms : r.stages.ms) CHECK(ms >= -1e-12);
          world.step(scene.world.dt_s);
        }
      }
    }
  }
}

TEST_CASE("on a clock that reads the work charged so far, each stage's time is its work", "[stages]") {
  // The cycle reads its clock when a stage changes, after the task's charge:
  // so with "time" = work charged to the step's budget, a stage's time must
  // equal its work, and apply (the rest of the step) must be 0. A task
  // attributed to the wrong stage, or a missed close, breaks the equality.
  for (const auto& [scene_name, scene] : test::collision_scenes()) {
    for (const char* method : {"interruptible", "interruptible_prioritized", "interruptible_tracked"}) {
      for (const auto& [fine, keep] : {std::pair{false, false}, {true, false}, {false, true}, {true, true}}) {
        INFO(scene_name << ", " << method << (fine ? " + fine_tasks" : "") << (keep ? " + keep_table" : ""));
        const MethodInfo& info = find_method(method);
        MethodSettings settings(info.settings);
        if (fine) settings.set("fine_tasks", true);
        if (keep) settings.set("keep_table", true);
        auto handler = info.make(settings);
        auto* cycle_handler = dynamic_cast<CycleHandler*>(handler.get());
        REQUIRE(cycle_handler);
        World world = build_world(scene.world);
        handler->init(world, test::settings_of(world, scene));
        const Budget* current = nullptr;
        cycle_handler->set_clock([&current] { return current ? static_cast<double>(current->spent()) : 0.0; });
        // A fifth of a whole cycle's work a step: cycles span steps and complete.
        std::uint64_t cycle_work = 0;
        {
          World probe = build_world(scene.world);
          auto whole = info.make(settings);
          whole->init(probe, test::settings_of(probe, scene));
          Budget unlimited = Budget::unlimited();
          cycle_work = whole->step(probe, unlimited).work_units;
        }
        bool saw_interruption = false, saw_completion = false;
        for (int s = 0; s < 30; ++s) {
          Budget budget = Budget::work_units(std::max<std::uint64_t>(1, cycle_work / 5));
          current = &budget;
          const StepReport r = handler->step(world, budget);
          for (std::size_t k = 0; k < kCostStages; ++k) CHECK(r.stages.ms[k] == static_cast<double>(r.stages.work[k]));
          CHECK(r.stages.ms_of(CostStage::Apply) == 0.0);
          if (r.cycle_done) {
            saw_completion = true;
            CHECK(r.stages.interrupted == -1);
          } else if (r.work_units > 0) {
            saw_interruption = true;
            CHECK(r.stages.interrupted == reported(cycle_handler->cycle().stage()));
          }
          world.step(scene.world.dt_s);
        }
        CHECK(saw_interruption);
        CHECK(saw_completion);
      }
    }
  }
}

TEST_CASE("stage names are the columns' names", "[stages]") {
  CHECK(cost_stage_name(CostStage::HashTets) == "hash_tets");
  CHECK(cost_stage_name(CostStage::Apply) == "apply");
  CHECK(static_cast<std::size_t>(CostStage::Apply) + 1 == kCostStages);
}
