#include "experiments/run/run_scene.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <set>
#include <cmath>
#include <limits>

#include "baselines/registry.hpp"
#include "experiments/metrics/distribution.hpp"
#include "experiments/metrics/jitter.hpp"
#include "experiments/metrics/latency.hpp"
#include "oracle/overlap_volume.hpp"
#include "oracle/triangle_pairs.hpp"
#include "oracle/tunneling.hpp"
#include "experiments/metrics/oracle_comparison.hpp"
#include "method/detection/spatial_hash.hpp"
#include "experiments/results/steps_csv.hpp"
#include "experiments/run/provenance.hpp"
#include "sim/io/atomic_file.hpp"
#include "sim/io/input_error.hpp"
#include "sim/mesh/vtu_writer.hpp"

namespace tcb {
namespace {

using Clock = std::chrono::steady_clock;
using Json = nlohmann::ordered_json;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

Json distribution_json(const std::vector<double>& values) {
  if (values.empty()) return nullptr;
  const Distribution d = summarize(values);
  return Json{{"mean", d.mean}, {"p50", d.p50}, {"p95", d.p95}, {"p99", d.p99}, {"max", d.max}};
}

// All bodies of the world as one VTU frame, for ParaView.
void write_frame(const World& world, const std::filesystem::path& path) {
  std::vector<Vec3> x, v;
  std::vector<Tet> tets;
  for (const Body& b : world.bodies) {
    const auto offset = static_cast<std::int32_t>(x.size());
    x.insert(x.end(), b.x_m.begin(), b.x_m.end());
    v.insert(v.end(), b.v_m_per_s.begin(), b.v_m_per_s.end());
    for (Tet t : b.mesh->tets) {
      for (auto& i : t) i += offset;
      tets.push_back(t);
    }
  }
  write_vtu(path, x, tets, {{"velocity_m_per_s", &v}});
}

Json scene_json(const SceneDesc& scene, const World& world) {
  Json objects = Json::array();
  for (const Body& b : world.bodies) {
    objects.push_back({{"name", b.name},
                       {"vertices", b.x_m.size()},
                       {"tets", b.mesh->tet_count()},
                       {"passive", b.passive},
                       {"model", b.passive ? "none" : to_string(b.material.model)},
                       {"integrator", b.passive ? "none" : to_string(b.material.integrator)}});
  }
  return Json{{"name", scene.name},
              {"file", scene.path.string()},
              {"ground", scene.ground.has_value()},
              {"objects", objects}};
}

}  // namespace

std::string budget_label(const BudgetSpec& budget) {
  switch (budget.kind) {
    case BudgetSpec::Kind::WallMs: return fmt::format("ms:{}", budget.value);
    case BudgetSpec::Kind::Work: return fmt::format("work:{}", static_cast<std::uint64_t>(budget.value));
    case BudgetSpec::Kind::None: break;
  }
  return "none";
}

std::optional<double> top_centre_height_m(const World& world) {
  const double g = world.gravity_m_per_s2.norm();
  const Vec3 up = g > 0.0 ? Vec3(-world.gravity_m_per_s2 / g) : Vec3(0.0, 1.0, 0.0);
  std::optional<double> top;
  for (const Body& b : world.bodies)
    if (!b.passive) top = std::max(top.value_or(-std::numeric_limits<double>::infinity()), centre_of_mass_m(b).dot(up));
  return top;
}

OracleSchedule parse_oracle_schedule(const std::string& text, const std::string& option) {
  if (text == "off") return {0};
  if (text == "every") return {1};
  if (text.rfind("every:", 0) == 0) {
    try {
      std::size_t used = 0;
      const long long k = std::stoll(text.substr(6), &used);
      if (used == text.size() - 6 && k >= 1) return {k};
    } catch (const std::exception&) {
    }
  }
  throw InputError(option, 0, "expected off, every or every:K with K >= 1, not '" + text + "'");
}

std::vector<std::pair<std::string, std::string>> available_methods() {
  std::vector<std::pair<std::string, std::string>> methods;
  for (const MethodInfo& m : method_registry()) methods.emplace_back(m.name, m.description);
  return methods;
}

RunOutcome run_scene(const SceneDesc& scene, const RunOptions& options) {
  const std::int64_t steps_total = options.steps.value_or(scene.steps);
  if (steps_total < 0) throw InputError("--steps", 0, "must not be negative");

  // Everything that can fail on bad input happens before the directory exists.
  std::unique_ptr<CollisionHandler> handler = make_handler(options.method, scene);
  World world = build_world(scene);
  const OracleSchedule overlap_schedule = options.overlap.value_or(options.oracle);
  TunnelingMeter tunneling(world);  // pairs interlocked at the start are not tunnelling when they end so
  const std::optional<double> top_centre_initial = top_centre_height_m(world);
  std::unique_ptr<SurfaceTrianglePairs> triangle_pairs;
  if (options.oracle.every > 0) triangle_pairs = std::make_unique<SurfaceTrianglePairs>(world);
  handler->init(world, scene);  // not timed
  JitterMeter jitter;
  LatencyMeter latency(world);
  const std::vector<std::string> warnings = handler->warnings();
  if (options.on_warning)
    for (const auto& w : warnings) options.on_warning(w);
  std::filesystem::create_directories(options.out_dir);
  const std::string started_at = utc_timestamp();
  const auto run_start = Clock::now();

  StepsCsv csv(options.out_dir / "steps.csv");
  std::vector<double> dynamics_ms, handling_ms, overshoot_pct, oracle_ms, recalls, precisions, depth_errors;
  double max_depth = 0.0;
  std::optional<double> overlap_max, probe_force_max;
  std::int64_t oracle_steps = 0, overlap_steps = 0, overlap_invalid_steps = 0;
  std::set<std::string> unmeasured;
  std::vector<double> solver_iterations, cycle_lengths;
  std::int64_t cycle_start_step = 1, depth_fallback_total = 0, colliding_max = 0;
  std::uint64_t work_total = 0;
  std::int64_t unconverged_steps = 0, nan_steps = 0;
  std::vector<PvdFrame> frames;
  RunOutcome outcome{"ok", "", 0, 0.0};
  dynamics_ms.reserve(steps_total);

  const auto record = [&](std::int64_t step) {
    if (options.record_every <= 0 || step % options.record_every != 0) return;
    std::filesystem::create_directories(options.out_dir / "frames");
    const std::string name = fmt::format("frames/frame_{:06d}.vtu", step);
    write_frame(world, options.out_dir / name);
    frames.push_back({world.time_s, name});
  };
  record(0);

  for (std::int64_t s = 0; s < steps_total; ++s) {
    StepRow row;
    Budget budget = options.budget.kind == BudgetSpec::Kind::WallMs ? Budget::wall_ms(options.budget.value)
                    : options.budget.kind == BudgetSpec::Kind::Work
                        ? Budget::work_units(static_cast<std::uint64_t>(options.budget.value))
                        : Budget::unlimited();
    const auto t_handler = Clock::now();
    StepReport report;
    try {
      report = handler->step(world, budget);
    } catch (const HashOverflow& e) {
      outcome = {"unstable", fmt::format("collision handling at step {}: {}", world.step_index + 1, e.what()), s, 0.0};
      break;
    }
    row.handling_ms = ms_since(t_handler);
    if (const auto probe = world.driven_contact_force_n()) {  // before step() clears the forces
      row.probe_force_x = probe->x();
      row.probe_force_y = probe->y();
      row.probe_force_z = probe->z();
      probe_force_max = std::max(probe_force_max.value_or(0.0), probe->norm());
    }
    if (options.oracle.due(world.step_index + 1)) {  // on the positions the handler just saw
      const auto t_oracle = Clock::now();
      const OracleFrame frame = compute_inside_oracle(world);
      latency.record_oracle(world.step_index + 1, frame);
      const OracleComparison cmp = compare_with_oracle(handler->contacts(), frame);
      row.oracle_points = cmp.oracle_points;
      row.recall = cmp.recall;
      row.precision = cmp.precision;
      row.depth_err_mean = cmp.depth_err_mean;
      row.depth_err_max = cmp.depth_err_max;
      row.max_depth = cmp.max_depth_m;
      row.triangle_pairs = static_cast<std::int64_t>(triangle_pairs->find(world).size());
      row.oracle_ms = ms_since(t_oracle);
      if (cmp.recall) recalls.push_back(*cmp.recall);
      if (cmp.precision) precisions.push_back(*cmp.precision);
      depth_errors.insert(depth_errors.end(), cmp.depth_errors.begin(), cmp.depth_errors.end());
      max_depth = std::max(max_depth, cmp.max_depth_m);
      unmeasured.insert(frame.unmeasured.begin(), frame.unmeasured.end());
      ++oracle_steps;
    }
    if (overlap_schedule.due(world.step_index + 1)) {
      const auto t_overlap = Clock::now();
      const OverlapFrame overlap = compute_overlap_volumes(world);
      tunneling.record_overlaps(overlap);
      ++overlap_steps;
      if (overlap.invalid.empty()) {
        row.overlap_volume = overlap.total_m3;
        overlap_max = std::max(overlap_max.value_or(0.0), overlap.total_m3);
      } else {
        ++overlap_invalid_steps;  // no value this step: never a silent 0
        unmeasured.insert(overlap.invalid.begin(), overlap.invalid.end());
      }
      row.oracle_ms = row.oracle_ms.value_or(0.0) + ms_since(t_overlap);
    }
    if (row.oracle_ms) oracle_ms.push_back(*row.oracle_ms);
    if (options.oracle.every == 1) latency.record_forces(world.step_index + 1, report.exact_points);
    const auto t0 = Clock::now();
    world.step(scene.dt_s);
    row.dynamics_ms = ms_since(t0);
    row.step = world.step_index;
    row.work_units = static_cast<std::int64_t>(report.work_units);
    row.cycle = report.cycle;
    row.cycle_done = report.cycle_done ? 1 : 0;
    row.colliding_points = report.colliding_points;
    row.exact_forces = report.exact_forces;
    row.estimated_forces = report.estimated_forces;
    handling_ms.push_back(*row.handling_ms);
    if (options.budget.kind == BudgetSpec::Kind::WallMs) {
      row.budget_ms = options.budget.value;
      if (options.budget.value > 0.0)
        overshoot_pct.push_back(100.0 * (*row.handling_ms - options.budget.value) / options.budget.value);
    }
    work_total += report.work_units;
    depth_fallback_total += report.depth_fallback;
    colliding_max = std::max(colliding_max, report.colliding_points);
    if (report.cycle_done) {
      cycle_lengths.push_back(static_cast<double>(row.step - cycle_start_step + 1));
      cycle_start_step = row.step + 1;
    }
    row.time_s = world.time_s;
    row.kinetic_energy = world.kinetic_energy_j();
    for (const Body& b : world.bodies) {
      if (!b.model) continue;
      row.solver_iterations += b.model->last_solver_iterations();
      if (!b.model->last_solve_converged()) ++unconverged_steps;
    }
    row.max_speed = world.max_speed_m_per_s();
    dynamics_ms.push_back(row.dynamics_ms);
    jitter.record(world, row.step, steps_total);
    solver_iterations.push_back(static_cast<double>(row.solver_iterations));
    csv.write(row);
    outcome.steps_done = s + 1;
    if (std::isnan(row.max_speed)) {
      ++nan_steps;
      outcome = {"unstable", fmt::format("non-finite position or velocity at step {}", row.step), s + 1, 0.0};
    } else if (row.max_speed > scene.max_speed_m_per_s) {
      outcome = {"unstable",
                 fmt::format("a vertex moves at {:.4g} m/s at step {}, above the scene's max_speed {:.4g} m/s",
                             row.max_speed, row.step, scene.max_speed_m_per_s),
                 s + 1, 0.0};
    }
    record(row.step);
    if (options.on_step) options.on_step(s + 1, steps_total);
    if (outcome.status != "ok") break;
  }
  csv.commit();
  if (!frames.empty()) write_pvd(options.out_dir / "frames.pvd", frames);
  outcome.wall_s = ms_since(run_start) / 1000.0;

  Json summary;
  summary["handling_ms"] = distribution_json(handling_ms);
  if (overshoot_pct.empty()) {
    summary["overshoot_pct"] = nullptr;  // no (positive) wall budget
  } else {
    const Distribution o = summarize(overshoot_pct);
    summary["overshoot_pct"] = {{"p50", o.p50}, {"p99", o.p99}, {"max", o.max}};
  }
  if (cycle_lengths.empty()) {
    summary["cycle_steps"] = nullptr;
  } else {
    const Distribution cycles = summarize(cycle_lengths);
    summary["cycle_steps"] = {{"mean", cycles.mean}, {"max", cycles.max}};
  }
  // Oracle figures: null when the oracle did not run (or had nothing to compare), never 0.
  const auto min_of = [](const std::vector<double>& v) -> Json {
    return v.empty() ? Json(nullptr) : Json(*std::min_element(v.begin(), v.end()));
  };
  const auto mean_of = [](const std::vector<double>& v) -> Json {
    return v.empty() ? Json(nullptr) : Json(summarize(v).mean);
  };
  summary["recall_min"] = min_of(recalls);
  summary["recall_mean"] = mean_of(recalls);
  summary["precision_min"] = min_of(precisions);
  if (depth_errors.empty()) {
    summary["depth_err"] = nullptr;
  } else {
    const Distribution e = summarize(depth_errors);
    summary["depth_err"] = {{"mean", e.mean}, {"rms", e.rms}, {"max", e.max}};
  }
  summary["max_depth"] = oracle_steps > 0 ? Json(max_depth) : Json(nullptr);
  summary["oracle_steps"] = oracle_steps;
  summary["oracle_ms"] = distribution_json(oracle_ms);
  // Whether a stack still stands: the highest centre of a dynamic body against
  // gravity, at the start and the end (a collapse need not be tunnelling).
  const std::optional<double> top_centre_final = top_centre_height_m(world);
  summary["top_centre_height_m"] =
      top_centre_initial && top_centre_final && std::isfinite(*top_centre_final)
          ? Json{{"initial", *top_centre_initial}, {"final", *top_centre_final}}
          : Json(nullptr);
  summary["jitter"] = scene.jitter_measure.empty() || jitter.samples() == 0 ? Json(nullptr) : Json(jitter.rms_m_per_s());
  if (std::isfinite(world.max_speed_m_per_s())) {
    const TunnelingResult tunnelled = tunneling.finish(world);
    summary["tunneling"] = tunnelled.pairs;
    unmeasured.insert(tunnelled.unmeasured.begin(), tunnelled.unmeasured.end());
  } else {
    summary["tunneling"] = nullptr;  // positions are not finite: nothing to judge
    unmeasured.insert("tunnelling: the final state is not finite");
  }
  // Between sparse oracle steps a vertex can leave and re-enter unseen, which
  // merges episodes and inflates latencies: only an every-step oracle measures it.
  if (options.oracle.every > 1) unmeasured.insert("latency_steps: needs --oracle every (sparse oracle steps merge episodes)");
  summary["oracle_unmeasured"] = std::vector<std::string>(unmeasured.begin(), unmeasured.end());
  if (options.oracle.every != 1) {
    summary["latency_steps"] = nullptr;
  } else {
    const Distribution l = summarize(latency.latencies());
    summary["latency_steps"] = latency.latencies().empty()
                                   ? Json(nullptr)
                                   : Json{{"mean", l.mean}, {"p95", l.p95}, {"max", l.max}};
    summary["unserved_penetrations"] = latency.unserved();
  }
  summary["overlap_volume_max"] = overlap_max ? Json(*overlap_max) : Json(nullptr);
  summary["probe_force_max"] = probe_force_max ? Json(*probe_force_max) : Json(nullptr);
  summary["overlap_steps"] = overlap_steps;
  summary["overlap_invalid_steps"] = overlap_invalid_steps;
  summary["nan_steps"] = nan_steps;
  summary["work_units_total"] = work_total;
  summary["colliding_points_max"] = colliding_max;
  summary["depth_fallback_points"] = depth_fallback_total;
  summary["dynamics_ms"] = distribution_json(dynamics_ms);
  summary["kinetic_energy_final"] = world.kinetic_energy_j();
  const Distribution iterations = summarize(solver_iterations);
  summary["solver"] = {{"iterations_mean", iterations.mean},
                       {"iterations_max", iterations.max},
                       {"unconverged_steps", unconverged_steps}};

  Json run;
  run["schema"] = "tcbench.run/1";
  run["scene"] = scene.name;
  run["method"] = options.method;
  switch (options.budget.kind) {
    case BudgetSpec::Kind::None: run["budget"] = {{"kind", "none"}, {"value", nullptr}}; break;
    case BudgetSpec::Kind::WallMs: run["budget"] = {{"kind", "wall_ms"}, {"value", options.budget.value}}; break;
    case BudgetSpec::Kind::Work:
      run["budget"] = {{"kind", "work"}, {"value", static_cast<std::uint64_t>(options.budget.value)}};
      break;
  }
  run["budget"]["label"] = options.budget_label.empty() ? budget_label(options.budget) : options.budget_label;
  run["steps"] = outcome.steps_done;
  run["steps_requested"] = steps_total;
  run["dt"] = scene.dt_s;
  run["seed"] = options.seed;
  const auto schedule_json = [](const OracleSchedule& o) {
    return o.every == 0 ? Json("off") : Json("every:" + std::to_string(o.every));
  };
  run["oracle"] = schedule_json(options.oracle);
  run["oracle_volume"] = schedule_json(overlap_schedule);
  run["overrides"] = options.overrides;
  run["command"] = options.command_line;
  run["build"] = build_info();
  run["machine"] = machine_info();
  run["started_at"] = started_at;
  run["wall_s"] = outcome.wall_s;
  run["warnings"] = warnings;
  run["status"] = outcome.status;
  run["unstable_reason"] = outcome.reason.empty() ? Json(nullptr) : Json(outcome.reason);
  run["world"] = scene_json(scene, world);
  run["summary"] = summary;
  write_file_atomically(options.out_dir / "run.json", run.dump(2) + "\n");
  return outcome;
}

}  // namespace tcb
