#include "experiments/run/run_scene.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <exception>
#include <optional>

#include "baselines/registry.hpp"
#include "experiments/metrics/meters.hpp"
#include "experiments/run/peak_memory.hpp"
#include "experiments/run/provenance.hpp"
#include "experiments/results/replay_file.hpp"
#include "experiments/run/run_record.hpp"
#include "experiments/run/thread_clock.hpp"
#include "method/detection/spatial_hash.hpp"
#include "sim/io/input_error.hpp"
#include "sim/parallel/core_handover.hpp"
#include "sim/world/perturbation.hpp"

namespace tcb {
namespace {

using Clock = std::chrono::steady_clock;
using Json = nlohmann::ordered_json;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

Json world_json(const SceneDesc& scene, const World& world) {
  Json objects = Json::array();
  for (const Body& b : world.bodies) {
    objects.push_back({{"name", b.name},
                       {"vertices", b.x_m.size()},
                       {"tets", b.mesh->tet_count()},
                       {"passive", b.passive},
                       {"latent", b.latent ? Json{{"family", b.latent->family},
                                                  {"model", b.latent->model_path.string()}}
                                           : Json(nullptr)},
                       {"model", b.passive ? "none" : to_string(b.material.model)},
                       {"integrator", b.passive ? "none" : to_string(b.material.integrator)}});
  }
  return Json{{"name", scene.name},
              {"file", scene.path.string()},
              {"ground", scene.world.ground.has_value()},
              {"mesh_order", to_string(scene.world.mesh_order)},
              {"objects", objects}};
}

// {bytes_key: bytes, tets, bytes_per_tet} over the world's tets (every
// body's, passive ones too: the figure a user sizes a machine by).
Json per_tet_json(const char* bytes_key, std::uint64_t bytes, const World& world) {
  std::uint64_t tets = 0;
  for (const Body& b : world.bodies) tets += b.mesh->tet_count();
  return Json{{bytes_key, bytes},
              {"tets", tets},
              {"bytes_per_tet", tets ? Json(static_cast<double>(bytes) / static_cast<double>(tets)) : Json(nullptr)}};
}

// The process's peak resident memory by the end of the run (oracle and
// solver included), per tet.
Json peak_memory_json(const World& world) {
  const std::optional<std::uint64_t> peak = peak_resident_bytes();
  return peak ? per_tet_json("resident_bytes", *peak, world) : Json(nullptr);
}

// The handler's own data at the end of the run (its containers only grow, so
// this is their peak), per tet; null for a method that does not count it.
Json collision_memory_json(const World& world, const CollisionHandler& handler) {
  const std::optional<std::size_t> bytes = handler.memory_bytes();
  return bytes ? per_tet_json("bytes", *bytes, world) : Json(nullptr);
}

Json settings_json(const MethodSettings& settings) {
  Json out = Json::object();
  // Not a structured binding: clang 14 (the fuzz preset) cannot capture one in a lambda.
  for (const auto& entry : settings.values()) std::visit([&](const auto& v) { out[entry.first] = v; }, entry.second);
  return out;
}

Json jitter_json(const Jitter& j) {
  return {{"position_m", j.position_m},
          {"velocity_m_per_s", j.velocity_m_per_s},
          {"rotation_rad", j.rotation_rad},
          {"material_rel", j.material_rel}};
}

Json vec3_json(const Vec3& v) { return Json::array({v.x(), v.y(), v.z()}); }

/// What [perturb] asked for and what each body drew (perturbation.hpp).
Json perturbation_json(const Perturbation& asked, const std::vector<BodyPerturbation>& drawn, const World& world) {
  Json bodies = Json::array();
  for (std::size_t b = 0; b < drawn.size(); ++b)
    bodies.push_back({{"name", world.bodies[b].name},
                      {"jitter", jitter_json(drawn[b].jitter)},
                      {"offset_m", vec3_json(drawn[b].offset_m)},
                      {"velocity_m_per_s", vec3_json(drawn[b].velocity_m_per_s)},
                      {"rotation_rad", vec3_json(drawn[b].rotation_rad)},
                      {"youngs_modulus_factor", drawn[b].youngs_modulus_factor}});
  return {{"jitter", jitter_json(asked.global)}, {"bodies", bodies}};
}

std::vector<std::string> scene_overrides(const std::vector<std::string>& overrides) {
  std::vector<std::string> scene_only;
  for (const std::string& o : overrides)
    if (o.rfind("method.", 0) != 0) scene_only.push_back(o);
  return scene_only;
}

}  // namespace

RunOutcome run_scene(const SceneDesc& scene, const RunOptions& options) {
  const std::int64_t steps_total = options.steps.value_or(scene.steps);
  if (steps_total < 0) throw InputError("--steps", 0, "must not be negative");

  // Everything that can fail on bad input happens before the directory exists.
  const MethodInfo& method = find_method(options.method);
  // Where the cycle may run on several threads, how cheaply the cores hand
  // each other what they wrote, before the run and after it: the
  // hypervisor's placement of the vCPUs, which moved the dog pair's 2-thread
  // cycle time by 20-40 % on the development VM (sim/parallel/core_handover.hpp).
  // Before the world is built, and after the meters' summaries and the
  // memory figures, so the probe's pool, buffers and cache traffic touch no
  // timed interval and no figure but the process's peak, which includes its
  // 4.25 MiB only where the run stays below that; none where the run is
  // pinned (its threads share one CPU). A probe that fails (no thread, no
  // memory) records null: it must not cost a finished run its record.
  const bool split = method.detects && scene.collision.threads > 1;
  const auto handover_ratio = [&]() -> Json {
    if (!split || options.pin_cpu) return nullptr;
    try {
      const std::optional<double> ratio = probe_handover_ratio();
      return ratio ? Json(*ratio) : Json(nullptr);
    } catch (const std::exception&) {
      return nullptr;
    }
  };
  const Json handover_start = handover_ratio();
  const auto table = scene.methods.find(options.method);
  const MethodSettings settings = table != scene.methods.end() ? table->second : MethodSettings(method.settings);
  std::unique_ptr<CollisionHandler> handler = method.make(settings);
  World world = build_world(scene.world);
  const std::vector<BodyPerturbation> perturbed = perturb_world(world, scene.perturb, options.seed);

  std::optional<ScopedPin> pin;  // undone when the run returns
  if (options.pin_cpu) {
    pin.emplace(*options.pin_cpu);
    if (!pin->error().empty()) throw InputError("--pin", 0, pin->error());
  }
  const CollisionSettings collision =
      resolve_collision_settings(world, scene.collision, scene.world.dt_s,
                                 scene.path.empty() ? std::string("scene") : scene.path.string());
  const RunSetup setup{scene,       world, options.budget, options.oracle, options.overlap.value_or(options.oracle),
                       steps_total, options.force_reference, &collision, options.reference_dir,
                       options.timing_floor};
  const std::vector<std::unique_ptr<Meter>> meters = make_meters(setup);
  handler->init(world, collision);  // not timed
  // Doubtful collision settings matter only to a method that handles collisions.
  std::vector<std::string> warnings = world.build_warnings;
  if (method.detects) warnings.insert(warnings.end(), collision.warnings.begin(), collision.warnings.end());
  if (options.on_warning)
    for (const auto& w : warnings) options.on_warning(w);

  std::vector<ColumnSpec> columns;
  for (const auto& m : meters)
    for (ColumnSpec& c : m->columns()) columns.push_back(std::move(c));
  RunRecord record(options.out_dir, columns, options.record_every, world, options.trajectory_every);
  std::optional<ReplayWriter> replay;  // with the VTU frames: the viewer's replay (results/replay_file.hpp)
  if (options.record_every > 0)
    replay.emplace(options.out_dir, world, options.record_every,
                   options.record_debug ? std::optional<double>(collision.detection.cell_size_m) : std::nullopt);
  const std::string started_at = utc_timestamp();
  const auto run_start = Clock::now();
  RunOutcome outcome{"ok", "", 0, 0.0};

  for (std::int64_t s = 0; s < steps_total; ++s) {
    if (options.before_step) options.before_step(world);
    Budget budget = options.budget.start();
    // The thread clocks are read inside the wall interval, so CPU time <= wall
    // time up to the clocks' resolution (handling_cpu_ms, timing_meter.hpp).
    const std::int64_t switches_before = thread_involuntary_switches();
    const auto t_handler = Clock::now();
    const double cpu_before_ms = thread_cpu_ms();
    StepReport report;
    try {
      report = handler->step(world, budget);
    } catch (const HashOverflow& e) {
      outcome = {"unstable", fmt::format("collision handling at step {}: {}", world.step_index + 1, e.what()), s, 0.0};
      break;
    }
    const double cpu_after_ms = thread_cpu_ms();
    const double handling_ms = ms_since(t_handler);
    const std::int64_t switches = thread_involuntary_switches() - switches_before;
    StepRow row = record.row();
    StepContext ctx{.step = world.step_index + 1,
                    .world = world,
                    .handler = *handler,
                    .report = report,
                    .handling_ms = handling_ms,
                    .handling_cpu_ms = cpu_after_ms - cpu_before_ms,
                    .handling_switches = switches,
                    .budget = &budget,
                    .row = row};
    for (const auto& m : meters) m->before_dynamics(ctx);
    if (replay) replay->record(ctx.step, world, *handler, report, ctx.oracle);
    const auto t_dynamics = Clock::now();
    world.step(scene.world.dt_s);
    ctx.dynamics_ms = ms_since(t_dynamics);
    ctx.max_speed_m_per_s = world.max_speed_m_per_s();
    ctx.kinetic_energy_j = world.kinetic_energy_j();
    for (const auto& m : meters) m->on_step(ctx);
    record.write_step(std::move(row), world);
    outcome.steps_done = s + 1;
    if (!ctx.unstable.empty()) outcome = {"unstable", ctx.unstable, s + 1, 0.0};
    if (options.on_step) options.on_step(s + 1, steps_total);
    const bool go_on = !options.after_step || options.after_step(ctx);  // the unstable step too: the page shows it
    if (outcome.status != "ok" || !go_on) break;
  }
  outcome.wall_s = ms_since(run_start) / 1000.0;

  Json summary = Json::object();
  summary["oracle_unmeasured"] = Json::array();  // meters add their reasons
  for (const auto& m : meters) m->summarize(summary);
  std::vector<std::string> unmeasured = summary["oracle_unmeasured"];
  std::sort(unmeasured.begin(), unmeasured.end());
  unmeasured.erase(std::unique(unmeasured.begin(), unmeasured.end()), unmeasured.end());
  summary["oracle_unmeasured"] = unmeasured;
  const Json peak_memory = peak_memory_json(world);
  const Json collision_memory = collision_memory_json(world, *handler);
  const Json handover_end = handover_ratio();

  Json run;
  run["schema"] = "tcbench.run/2";
  run["scene"] = scene.name;
  run["method"] = options.method;
  run["settings"] = settings_json(settings);
  run["method_label"] = method_label(options.method, method.settings, settings);
  run["budget"] = {{"kind", options.budget.kind_name()},
                   {"value", options.budget.kind == BudgetKind::None ? Json(nullptr)
                             : options.budget.kind == BudgetKind::Work
                                 ? Json(static_cast<std::uint64_t>(options.budget.value))
                                 : Json(options.budget.value)},
                   {"label", options.budget_label.empty() ? options.budget.label() : options.budget_label}};
  run["steps"] = outcome.steps_done;
  run["steps_requested"] = steps_total;
  run["dt"] = scene.world.dt_s;
  run["response"] = scene.collision.response_mode == ResponseMode::Implicit ? "implicit" : "explicit";
  run["seed"] = options.seed;
  run["perturbation"] = perturbation_json(scene.perturb, perturbed, world);
  run["collision"] = {{"cell_size_m", collision.detection.cell_size_m},
                      {"mean_edge_m", collision.mean_edge_m},
                      {"table_size", collision.detection.table_size},
                      {"tets", collision.tets},
                      {"hash", collision.detection.hash == HashFunction::Paper ? "paper" : "mixed"},
                      {"threads", collision.threads},
                      {"handover_ratio",
                       split ? Json{{"start", handover_start}, {"end", handover_end}} : Json(nullptr)}};
  run["pin"] = options.pin_cpu ? Json(*options.pin_cpu) : Json(nullptr);
  run["oracle"] = setup.oracle.label();
  run["oracle_volume"] = setup.overlap.label();
  run["force_reference"] = setup.force_reference.label();
  run["trajectory"] = options.trajectory_every > 0 ? Json{{"every", options.trajectory_every}, {"file", "trajectory.bin"}}
                                                   : Json(nullptr);
  run["replay"] = options.record_every > 0
                      ? Json{{"every", options.record_every}, {"file", "replay.bin"}, {"manifest", "replay.json"}}
                      : Json(nullptr);
  run["reference"] = options.reference_dir.empty() ? Json(nullptr) : Json(options.reference_dir.string());
  run["overrides"] = scene_overrides(options.overrides);
  run["command"] = options.argv;
  run["build"] = build_info();
  run["machine"] = machine_info();
  run["started_at"] = started_at;
  run["wall_s"] = outcome.wall_s;
  run["warnings"] = warnings;
  run["status"] = outcome.status;
  run["unstable_reason"] = outcome.reason.empty() ? Json(nullptr) : Json(outcome.reason);
  run["world"] = world_json(scene, world);
  run["peak_memory"] = peak_memory;
  run["collision_memory"] = collision_memory;
  const auto counts = handler->cycle_counts();
  run["cycles"] = counts ? Json{{"begun", counts->begun}, {"tet_hashes_fresh", counts->tet_hashes_fresh}} : Json(nullptr);
  run["summary"] = summary;
  if (replay) replay->finish();
  record.finish(run);
  return outcome;
}

}  // namespace tcb
