#include "baselines/registry.hpp"

#include "baselines/every_nth_handler.hpp"
#include "baselines/fcl_tets_handler.hpp"
#include "baselines/full_handler.hpp"
#include "baselines/none_handler.hpp"
#include "method/handler/interruptible_handler.hpp"
#include "method/neural/neural_handler.hpp"
#include "sim/io/input_error.hpp"

namespace tcb {

namespace {

// Ours, on every interruptible method: finer tasks, so a budget is met more closely.
const SettingSpec kFineTasks{.name = "fine_tasks",
                             .type = SettingSpec::Type::Boolean,
                             .default_value = false,
                             .description = "hash the tets and build the hash tables in small resumable tasks "
                                            "instead of the paper's one task each (ours, not the paper's)"};

const SettingSpec kReserveApply{.name = "reserve_apply",
                                .type = SettingSpec::Type::Boolean,
                                .default_value = false,
                                .description = "under a wall-clock budget, stop the cycle early by the time applying "
                                               "the forces took in recent steps, so the step ends within the budget "
                                               "(ours, not the paper's)"};

const SettingSpec kApplyFirst{.name = "apply_first",
                              .type = SettingSpec::Type::Boolean,
                              .default_value = false,
                              .description = "apply the forces at the start of each step, from the cycle as the last "
                                             "step left it, and give the cycle the rest of the budget: a wall-clock "
                                             "budget then sees the applying, and a depth acts one step later (ours, "
                                             "not the paper's)"};

const SettingSpec kWidenStale{.name = "widen_stale",
                              .type = SettingSpec::Type::Boolean,
                              .default_value = false,
                              .description = "once a cycle spans steps, grow its point queries and border-edge "
                                             "searches by how far the hashed elements can have moved since, so none "
                                             "is missed for being hashed where it was (ours, not the paper's)"};

const SettingSpec kRehashStale{.name = "rehash_stale",
                               .type = SettingSpec::Type::Boolean,
                               .default_value = false,
                               .description = "once a cycle spans steps, refresh the tet hash before querying in a "
                                              "later step: every moving tet's box, and the tets that left their "
                                              "cells entered into a second table (ours, not the paper's)"};

const SettingSpec kKeepTable{.name = "keep_table",
                             .type = SettingSpec::Type::Boolean,
                             .default_value = false,
                             .description = "keep the tet hash from one cycle to the next and refresh it (every moving "
                                            "tet's box, the tets that left their cells entered into a second table) "
                                            "instead of hashing every tet afresh; the same contacts in a cycle "
                                            "within one step, less hashing work (ours, not the paper's)"};

const SettingSpec kPredictTasks{.name = "predict_tasks",
                                .type = SettingSpec::Type::Boolean,
                                .default_value = false,
                                .description = "under a wall-clock budget, also stop before a task predicted (from the "
                                               "recent times of its stage's tasks) to end past the budget, instead of "
                                               "only after the task that reached it (ours, not the paper's)"};

InterruptibleHandler::Options interruptible_options(const MethodSettings& s, std::int64_t keep_lost_cycles = 0) {
  return {.keep_lost_cycles = keep_lost_cycles,
          .schedule = {.granularity = s.boolean("fine_tasks") ? TaskGranularity::fine_tasks() : TaskGranularity{},
                       .widen_stale = s.boolean("widen_stale"),
                       .rehash_stale = s.boolean("rehash_stale"),
                       .keep_table = s.boolean("keep_table"),
                       .predict_tasks = s.boolean("predict_tasks")},
          .reserve_apply = s.boolean("reserve_apply"),
          .apply_first = s.boolean("apply_first")};
}

}  // namespace

const std::vector<MethodInfo>& method_registry() {
  using Stale = InterruptibleHandler::Stale;
  static const std::vector<MethodInfo> registry = {
      {.name = "interruptible",
       .description = "the paper's method: the cycle under a time budget, resumed next step, forces extrapolated "
                      "meanwhile",
       .settings = {kFineTasks, kReserveApply, kApplyFirst, kWidenStale, kRehashStale, kKeepTable, kPredictTasks},
       .make =
           [](const MethodSettings& s) {
             return std::make_unique<InterruptibleHandler>(Stale::Extrapolate, interruptible_options(s));
           },
       .uses_budget = true},
      {.name = "interruptible_no_extrapolation",
       .description = "ablation: interruptible without force extrapolation",
       .settings = {kFineTasks, kReserveApply, kApplyFirst, kWidenStale, kRehashStale, kKeepTable, kPredictTasks},
       .make =
           [](const MethodSettings& s) {
             return std::make_unique<InterruptibleHandler>(Stale::Nothing, interruptible_options(s));
           },
       .uses_budget = true},
      {.name = "interruptible_tracked",
       .description = "variant (not in the paper): interruptible, but contacts known from earlier steps get the "
                      "penalty force of their depth tracked with the current positions instead of an extrapolated "
                      "force",
       .settings = {{.name = "keep_lost_cycles",
                     .type = SettingSpec::Type::Integer,
                     .default_value = std::int64_t{1},
                     .min = 0,
                     .max = 1e6,
                     .description = "a tracked contact that a completed cycle no longer finds stays (inert while its "
                                    "tracked depth is <= 0) for this many more cycles; 0: forgotten at once, like "
                                    "the paper's history"},
                    kFineTasks,
                    kReserveApply,
                    kApplyFirst,
                    kWidenStale, kRehashStale, kKeepTable, kPredictTasks},
       .make =
           [](const MethodSettings& s) {
             return std::make_unique<InterruptibleHandler>(Stale::Track,
                                                           interruptible_options(s, s.integer("keep_lost_cycles")));
           },
       .uses_budget = true},
      {.name = "interruptible_prioritized",
       .description = "variant (not in the paper; its future work): interruptible, but each cycle queries the "
                      "fastest points first, so they get their depth and force first",
       .settings = {kFineTasks, kReserveApply, kApplyFirst, kWidenStale, kRehashStale, kKeepTable, kPredictTasks},
       .make =
           [](const MethodSettings& s) {
             InterruptibleHandler::Options options = interruptible_options(s);
             options.schedule.order = WorkOrder::FastestFirst;
             return std::make_unique<InterruptibleHandler>(Stale::Extrapolate, options);
           },
       .uses_budget = true},
      {.name = "full",
       .description = "the whole collision cycle every step, never interrupted (with default settings the paper's "
                      "reference)",
       .settings = {kKeepTable},
       .make =
           [](const MethodSettings& s) {
             return std::make_unique<FullHandler>(DetectionMode::SpatialHash,
                                                  CycleSchedule{.keep_table = s.boolean("keep_table")});
           }},
      {.name = "every_nth",
       .description = "a full cycle every n-th step, the last forces held in between",
       .settings = {{.name = "n",
                     .type = SettingSpec::Type::Integer,
                     .default_value = std::int64_t{2},
                     .min = 1,
                     .max = 1e6,
                     .description = "a full cycle on every n-th step (1: every step)"},
                    {.name = "hold",
                     .type = SettingSpec::Type::Boolean,
                     .default_value = true,
                     .description = "between cycles, apply the last cycle's forces again (false: none)"}},
       .make =
           [](const MethodSettings& s) { return std::make_unique<EveryNthHandler>(s.integer("n"), s.boolean("hold")); }},
      {.name = "fcl_tets",
       .description = "baseline an FCL user would write: every tet an FCL Convex in a dynamic AABB tree, tet pairs "
                      "through libccd's GJK+EPA, a penalty force per pair spread over both tets; under a budget the "
                      "pair loop stops, no extrapolation. Reports the vertices of colliding tets (recall: a vertex "
                      "inside is found when a tet around it is in a pair; precision counts the others)",
       .make = [](const MethodSettings&) { return std::make_unique<FclTetsHandler>(); },
       .uses_budget = true,
       .reports = MethodInfo::Reports::TetPairVertices},
      {.name = "neural",
       .description = "seed 002's learned self-collision detector: one network evaluation per latent-driven object "
                      "and step (the scene's latent_model), a whole-object verdict, no points and no forces; judged "
                      "per frame by the oracle (self_frames)",
       .make = [](const MethodSettings&) { return std::make_unique<NeuralHandler>(); },
       // It obeys a budget (an evaluation is skipped once it is spent), but one
       // evaluation per object never needs one: sweeps run it once, budget none.
       .reports = MethodInfo::Reports::BodyVerdicts},
      {.name = "brute_force",
       .description = "every point against every tet, no hashing: the O(n^2) reference for tests",
       .make = [](const MethodSettings&) { return std::make_unique<FullHandler>(DetectionMode::BruteForce); }},
      {.name = "none",
       .description = "no collision handling: objects pass through each other (dynamics and ground only)",
       .make = [](const MethodSettings&) { return std::make_unique<NoneHandler>(); },
       .detects = false},
  };
  return registry;
}

const MethodInfo& find_method(const std::string& name) {
  std::string names;
  for (const MethodInfo& m : method_registry()) {
    if (m.name == name) return m;
    names += (names.empty() ? "" : ", ") + m.name;
  }
  throw InputError("--method", 0, "unknown method '" + name + "' (available: " + names + ")");
}

std::unique_ptr<CollisionHandler> make_handler(const std::string& name, const MethodSettings* settings) {
  const MethodInfo& m = find_method(name);
  return m.make(settings ? *settings : MethodSettings(m.settings));
}

}  // namespace tcb
