#pragma once
/// Where a step's handling time and work go: per stage of the collision cycle
/// (collision_cycle.hpp), plus `apply`, everything the handler does outside
/// the cycle (applying forces, extrapolating, its bookkeeping). Issue 20's
/// stage costs; the run records them per step (experiments/metrics/stage_meter).
///
/// Stages as reported merge the cycle's internal ones that do the same job:
/// hash_tets = HashTets + BuildTetHash, hash_surface = HashSurface +
/// BuildSurfaceHash, propagate = Propagate + BuildLayer. A task's time and
/// work go to the stage it started in. Times are read on the handler's clock
/// only when the stage changes (and when a step's handling starts and ends),
/// so recording costs a few clock reads a step, not one a task.
///
/// Contract: the work of the stages adds up exactly to the work the cycle
/// charged to the step's budget; the times of all stages, apply included, add
/// up exactly to the span between the handler's first and last clock read of
/// the step (ms), which lies inside the run loop's handling interval.

#include <array>
#include <cstdint>
#include <string_view>

namespace tcb {

enum class CostStage : std::uint8_t {
  Prioritize,
  HashTets,
  QueryPoints,
  HashSurface,
  BorderDepth,
  Propagate,
  Forces,
  Apply,
};
inline constexpr std::size_t kCostStages = 8;

/// "prioritize", "hash_tets", "query_points", "hash_surface", "border_depth",
/// "propagate", "forces", "apply": the names steps.csv and the summary use.
std::string_view cost_stage_name(CostStage stage);

struct StageCosts {
  std::array<double, kCostStages> ms{};
  std::array<std::uint64_t, kCostStages> work{};
  /// The stage the cycle stopped in because the budget expired (it resumes
  /// there); -1 when it was not interrupted this step.
  int interrupted = -1;

  double total_ms() const;
  std::uint64_t total_work() const;
  double& ms_of(CostStage s) { return ms[static_cast<std::size_t>(s)]; }
  std::uint64_t& work_of(CostStage s) { return work[static_cast<std::size_t>(s)]; }
  double ms_of(CostStage s) const { return ms[static_cast<std::size_t>(s)]; }
  std::uint64_t work_of(CostStage s) const { return work[static_cast<std::size_t>(s)]; }
};

}  // namespace tcb
