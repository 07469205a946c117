#pragma once
/// A meter measures one metric of a run (handling time, the oracle
/// comparison, latency, jitter, ...). The run loop (experiments/run/run_scene.cpp)
/// calls every registered meter (meters.cpp) at two points of each step and
/// once at the end:
///
///   handler.step(world, budget)        timed: handling_ms
///   before_dynamics(ctx)               the positions the handler just saw
///   world.step(dt)                     timed: dynamics_ms
///   on_step(ctx)                       the integrated state
///   ... after the last step: summarize(summary)
///
/// A meter writes only the steps.csv columns it declares in columns() and the
/// summary keys it owns; summary.csv and `tcbench check` pick every summary
/// key up without further registration. Oracle work done by a meter is timed
/// as oracle_ms and is never handling time. A meter that finds the run
/// unstable says why in StepContext::unstable; the loop stops after that step.
/// Adding a metric: one meter (.hpp/.cpp here) and one line in meters.cpp.

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "experiments/results/steps_csv.hpp"
#include "experiments/scene/scene_desc.hpp"
#include "method/handler/budget.hpp"
#include "method/handler/collision_handler.hpp"

namespace tcb {

struct OracleFrame;
struct OverlapFrame;

/// When an oracle computation runs: never (every = 0), or on every k-th step.
struct OracleSchedule {
  std::int64_t every = 0;
  bool due(std::int64_t step) const { return every > 0 && step % every == 0; }
  /// "off" or "every:K", as run.json records it.
  std::string label() const { return every == 0 ? "off" : "every:" + std::to_string(every); }
};

/// Parses "off", "every" or "every:K"; InputError naming `option` otherwise.
OracleSchedule parse_oracle_schedule(const std::string& text, const std::string& option = "--oracle");

/// What every meter may know of the run, fixed for its whole length.
struct RunSetup {
  const SceneDesc& scene;
  /// The run's world: its initial state when the meters are made, then the
  /// state as it evolves (meters may keep this reference for summarize()).
  const World& world;
  BudgetSpec budget;
  OracleSchedule oracle;   ///< inside sets, depths, triangle pairs
  OracleSchedule overlap;  ///< exact overlap volume (corefinement)
  std::int64_t steps_total = 0;
  OracleSchedule force_reference{};  ///< shadow full cycles (force_reference_meter.hpp)
  /// The collision settings the run resolved (null: none, e.g. in tests).
  const CollisionSettings* collision = nullptr;
  /// A reference run's directory (--reference): divergence_meter.hpp. Empty: none.
  std::filesystem::path reference_dir{};
  bool timing_floor = true;  ///< RunOptions::timing_floor
};

/// One step as the meters see it.
struct StepContext {
  std::int64_t step = 0;  ///< 1-based number of the step being run
  const World& world;
  const CollisionHandler& handler;
  const StepReport& report;
  double handling_ms = 0.0;
  double handling_cpu_ms = 0.0;          ///< the handling thread's CPU time over the same interval
  std::int64_t handling_switches = 0;    ///< its involuntary context switches during handling
  const Budget* budget = nullptr;        ///< the step's budget after handling (its granularity figures)
  double dynamics_ms = 0.0;  ///< set before on_step()
  /// The integrated state's fastest vertex (m/s; NaN when not finite) and
  /// kinetic energy (J), computed once after world.step for every meter.
  double max_speed_m_per_s = 0.0, kinetic_energy_j = 0.0;
  StepRow& row;
  /// Oracle frames computed this step (before_dynamics), for the meters that
  /// need the truth: null when the oracle did not run.
  const OracleFrame* oracle = nullptr;
  const OverlapFrame* overlap = nullptr;
  /// Set by a meter that finds the state unstable: why, in words.
  std::string unstable{};
};

class Meter {
 public:
  using Json = nlohmann::ordered_json;
  virtual ~Meter() = default;
  /// The steps.csv columns this meter writes.
  virtual std::vector<ColumnSpec> columns() const { return {}; }
  /// After handling, before integration: the positions the handler saw.
  virtual void before_dynamics(StepContext&) {}
  /// After integration.
  virtual void on_step(StepContext&) {}
  /// Adds this meter's keys to the run's summary (null, never 0, for what was
  /// not measured). Reasons something could not be measured go into the
  /// array summary["oracle_unmeasured"].
  virtual void summarize(Json& summary) const = 0;
};

/// Whether step (1-based) lies in the run's settled second half, where the
/// resting-contact measures (jitter, settling) are taken.
inline bool in_settled_half(std::int64_t step, std::int64_t steps_total) { return 2 * step > steps_total; }

/// Appends a reason to summary["oracle_unmeasured"].
void note_unmeasured(nlohmann::ordered_json& summary, const std::string& reason);

/// {mean, p50, p95, p99, max} of the values; null when there are none.
nlohmann::ordered_json distribution_json(const std::vector<double>& values);

}  // namespace tcb
