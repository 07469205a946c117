#include "experiments/run/run_scene.hpp"

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <map>
#include <set>

#include "experiments/results/steps_csv.hpp"
#include "experiments/results/trajectory_file.hpp"
#include "experiments/run/thread_clock.hpp"
#include "experiments/scene/scene_file.hpp"
#include "sim/io/atomic_file.hpp"
#include "sim/io/input_error.hpp"

using namespace tcb;
namespace fs = std::filesystem;

namespace {

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("tcbench_run_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  return dir;
}

std::vector<std::string> lines_of(const fs::path& file) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<std::string> cells_of(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line);
  for (std::string c; std::getline(in, c, ',');) out.push_back(c);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

// The cells of a steps.csv row without its timing columns (handling_ms,
// dynamics_ms, oracle_ms): everything else must be reproducible.
std::vector<std::string> without_timing(const std::string& header, const std::string& line) {
  const std::vector<std::string> cells = cells_of(line), names = cells_of(header);
  std::vector<std::string> kept;
  for (std::size_t i = 0; i < cells.size(); ++i)
    if (i >= names.size() || (!(names[i].size() >= 3 && names[i].substr(names[i].size() - 3) == "_ms") &&
                              names[i] != "handling_switches"))
      kept.push_back(cells[i]);
  return kept;  // every *_ms column is a timing, and so are the scheduler's context switches
}

SceneDesc small_drop() {
  return parse_scene(R"([scene]
dt = 0.001
steps = 50
[ground]
height = 0.0
[[object]]
name = "cube"
mesh = "box:size=0.1x0.1x0.1,cells=2x2x2"
position = [0.0, 0.2, 0.0]
)",
                     "small.toml");
}

}  // namespace

TEST_CASE("a run writes complete steps.csv and run.json", "[run]") {
  const fs::path dir = fresh_dir("ok");
  RunOptions options;
  options.out_dir = dir;
  options.seed = 7;
  options.record_every = 25;
  std::int64_t progress_calls = 0;
  options.on_step = [&](std::int64_t, std::int64_t) { ++progress_calls; };
  const RunOutcome outcome = run_scene(small_drop(), options);
  CHECK(outcome.status == "ok");
  CHECK(outcome.exit_code() == 0);
  CHECK(progress_calls == 50);

  const auto lines = lines_of(dir / "steps.csv");
  REQUIRE(lines.size() == 51);
  CHECK(lines[0].rfind("step,time_s,", 0) == 0);
  for (const char* column : {"step", "time_s", "handling_ms", "budget_ms", "work_units", "cycle", "cycle_done",
                             "colliding_points", "exact_forces", "estimated_forces", "oracle_points", "recall",
                             "precision", "depth_err_mean", "depth_err_max", "max_depth", "overlap_volume",
                             "kinetic_energy"})
    CHECK_THAT(lines[0], Catch::Matchers::Contains(column));
  // Handling is measured (the default method is full); the budget and the
  // oracle columns stay empty: nothing measured them.
  const auto names = cells_of(lines[0]);
  const auto first = cells_of(lines[1]);
  REQUIRE(first.size() == names.size());
  for (std::size_t i = 0; i < names.size(); ++i) {
    INFO(names[i]);
    const bool empty = names[i] == "budget_ms" || names[i] == "oracle_points" || names[i] == "recall" ||
                       names[i] == "precision" || names[i].rfind("depth_err", 0) == 0 || names[i] == "max_depth" ||
                       names[i] == "overlap_volume" || names[i] == "triangle_pairs" || names[i] == "oracle_ms" ||
                       names[i].rfind("probe_force", 0) == 0 ||  // no driven object in this scene
                       names[i] == "interrupted_stage" ||          // no budget: never interrupted
                       names[i].rfind("force_", 0) == 0 || names[i] == "reference_ms" ||  // no --force-reference
                       names[i].rfind("div_", 0) == 0;                                     // no --reference
    CHECK(first[i].empty() == empty);
  }

  const auto run = nlohmann::json::parse(read_file(dir / "run.json"));
  CHECK(run["schema"] == "tcbench.run/2");
  CHECK(run["method"] == "full");
  CHECK(run["method_label"] == "full");
  CHECK(run["settings"].is_object());
  CHECK(run["status"] == "ok");
  CHECK(run["steps"] == 50);
  CHECK(run["seed"] == 7);
  CHECK(run["budget"]["kind"] == "none");
  for (const char* key : {"git_sha", "dirty", "compiler", "flags", "build_type"}) CHECK(run["build"].contains(key));
  for (const char* key : {"cpu", "cores"}) CHECK(run["machine"].contains(key));
  for (const char* key : {"handling_ms", "overshoot_pct", "cycle_steps", "latency_steps", "recall_min", "recall_mean",
                          "precision_min", "depth_err", "max_depth", "overlap_volume_max", "jitter", "tunneling",
                          "nan_steps"})
    CHECK(run["summary"].contains(key));
  CHECK(run["summary"]["handling_ms"]["p50"].is_number());
  CHECK(run["summary"]["recall_min"].is_null());  // no oracle yet
  CHECK(run["summary"]["nan_steps"] == 0);
  // The dropped cube fell: its centre is lower at the end than at the start.
  CHECK(run["summary"]["top_centre_height_m"]["final"].get<double>() <
        run["summary"]["top_centre_height_m"]["initial"].get<double>());
  // The handling thread's CPU time lies inside the wall interval (the thread
  // clocks are read within it): never above it beyond the clocks' resolution.
  const auto column = [&](const char* name) {
    return static_cast<std::size_t>(std::find(names.begin(), names.end(), name) - names.begin());
  };
  const std::size_t wall = column("handling_ms"), cpu = column("handling_cpu_ms"), sw = column("handling_switches");
  REQUIRE(cpu < names.size());
  REQUIRE(sw < names.size());
  for (std::size_t l = 1; l < lines.size(); ++l) {
    const auto cells = cells_of(lines[l]);
    INFO("step " << l);
    CHECK(std::stod(cells[cpu]) <= std::stod(cells[wall]) + 1e-3);  // 1 us
    CHECK(std::stod(cells[cpu]) >= 0.0);
    CHECK(std::stoll(cells[sw]) >= 0);
  }
  CHECK(run["summary"]["timing"]["verdict"].is_string());
  CHECK(run["pin"].is_null());
  CHECK(run["summary"]["max_task_us"].is_null());  // no wall budget: no clock read
  // A pinned run records its CPU and gives the thread its affinity back.
  const std::optional<int> before = pinned_cpu();
  RunOptions pinned;
  pinned.out_dir = fresh_dir("pinned");
  pinned.steps = 3;
  pinned.pin_cpu = allowed_cpus().back();
  SceneDesc two_threads = small_drop();  // pinned, both share the one CPU: no handover between cores to probe
  two_threads.collision.threads = 2;
  REQUIRE(run_scene(two_threads, pinned).status == "ok");
  const auto pinned_run = nlohmann::json::parse(read_file(pinned.out_dir / "run.json"));
  CHECK(pinned_run["pin"] == *pinned.pin_cpu);
  CHECK(pinned_run["collision"]["handover_ratio"] == nlohmann::json{{"start", nullptr}, {"end", nullptr}});
  CHECK(pinned_run["summary"]["timing"]["pinned_cpu"] == *pinned.pin_cpu);
  CHECK(pinned_cpu() == before);
  fs::remove_all(pinned.out_dir);
  // A method that detects nothing has no cycle to split: no probe, whatever the threads.
  RunOptions idle;
  idle.method = "none";
  idle.out_dir = fresh_dir("idle_threads");
  idle.steps = 2;
  REQUIRE(run_scene(two_threads, idle).status == "ok");
  CHECK(nlohmann::json::parse(read_file(idle.out_dir / "run.json"))["collision"]["handover_ratio"].is_null());
  fs::remove_all(idle.out_dir);
  CHECK(fs::exists(dir / "frames.pvd"));
  CHECK(fs::exists(dir / "frames/frame_000050.vtu"));
  for (const auto& entry : fs::recursive_directory_iterator(dir)) CHECK(entry.path().extension() != ".tmp");
  fs::remove_all(dir);
}

TEST_CASE("an exploding run stops, says why, keeps its files and exits 1", "[run]") {
  const fs::path dir = fresh_dir("unstable");
  // An explicit mass-spring model with a time step far beyond its stability limit.
  const SceneDesc scene = parse_scene(R"([scene]
dt = 0.05
steps = 500
[[object]]
name = "cube"
mesh = "box:size=0.1x0.1x0.1,cells=2x2x2"
material = { model = "mass_spring", youngs_modulus = 1e7 }
)",
                                      "explode.toml");
  RunOptions options;
  options.out_dir = dir;
  const RunOutcome outcome = run_scene(scene, options);
  CHECK(outcome.status == "unstable");
  CHECK(outcome.exit_code() == 1);
  CHECK(outcome.steps_done < 500);
  const auto run = nlohmann::json::parse(read_file(dir / "run.json"));
  CHECK(run["status"] == "unstable");
  CHECK(run["steps"] == outcome.steps_done);
  CHECK_THAT(run["unstable_reason"].get<std::string>(), Catch::Matchers::Contains("max_speed"));
  CHECK(lines_of(dir / "steps.csv").size() == static_cast<std::size_t>(outcome.steps_done + 1));
  fs::remove_all(dir);
}

TEST_CASE("bad input fails before any result file exists", "[run]") {
  const fs::path dir = fresh_dir("bad");
  SceneDesc scene = small_drop();
  scene.world.objects[0].mesh = "nowhere.mesh";
  RunOptions options;
  options.out_dir = dir;
  CHECK_THROWS_AS(run_scene(scene, options), InputError);
  options.method = "no_such_method";
  CHECK_THROWS_WITH(run_scene(small_drop(), options), Catch::Matchers::Contains("unknown method"));
  CHECK_FALSE(fs::exists(dir));
}

TEST_CASE("runs are deterministic apart from timings", "[run]") {
  const fs::path a = fresh_dir("det_a"), b = fresh_dir("det_b");
  for (const auto& dir : {a, b}) {
    RunOptions options;
    options.out_dir = dir;
    run_scene(small_drop(), options);
  }
  const auto la = lines_of(a / "steps.csv"), lb = lines_of(b / "steps.csv");
  REQUIRE(la.size() == lb.size());
  for (std::size_t i = 1; i < la.size(); ++i) REQUIRE(without_timing(la[0], la[i]) == without_timing(lb[0], lb[i]));
  fs::remove_all(a);
  fs::remove_all(b);
}

TEST_CASE("seeds: without jitter every seed is the same run; with it the same seed repeats and others differ",
          "[run][perturb]") {
  const auto run_rows = [](const std::string& name, std::uint64_t seed, const std::vector<std::string>& sets) {
    const fs::path dir = fresh_dir(name);
    RunOptions options;
    options.out_dir = dir;
    options.seed = seed;
    options.steps = 30;
    const SceneDesc scene = parse_scene(R"([scene]
dt = 0.001
[ground]
height = 0.0
[[object]]
name = "cube"
mesh = "box:size=0.1x0.1x0.1,cells=2x2x2"
position = [0.0, 0.2, 0.0]
)",
                                        "small.toml", sets);
    REQUIRE(run_scene(scene, options).status == "ok");
    const auto lines = lines_of(dir / "steps.csv");
    std::vector<std::vector<std::string>> rows;
    for (std::size_t i = 1; i < lines.size(); ++i) rows.push_back(without_timing(lines[0], lines[i]));
    std::ifstream in(dir / "run.json");
    const nlohmann::json record = nlohmann::json::parse(in);
    fs::remove_all(dir);
    return std::make_pair(rows, record["perturbation"]);
  };
  const std::vector<std::string> jitter = {"perturb.position=0.01", "perturb.velocity=0.1", "perturb.rotation=0.1",
                                           "perturb.material=0.2"};
  const auto plain0 = run_rows("seed_plain0", 0, {}), plain9 = run_rows("seed_plain9", 9, {});
  CHECK(plain0.first == plain9.first);
  CHECK(plain0.second["bodies"][0]["offset_m"] == nlohmann::json::array({0.0, 0.0, 0.0}));
  const auto a = run_rows("seed_a", 3, jitter), again = run_rows("seed_again", 3, jitter),
             b = run_rows("seed_b", 4, jitter);
  CHECK(a.first == again.first);
  CHECK(a.second == again.second);
  CHECK(a.first != b.first);
  CHECK(a.first != plain0.first);
  // run.json records what was asked and what was drawn.
  CHECK(a.second["jitter"]["velocity_m_per_s"] == 0.1);
  const nlohmann::json& cube = a.second["bodies"][0];
  CHECK(cube["name"] == "cube");
  CHECK(cube["jitter"]["material_rel"] == 0.2);
  CHECK(cube["youngs_modulus_factor"].get<double>() != 1.0);
  CHECK(cube["offset_m"] != b.second["bodies"][0]["offset_m"]);
}

TEST_CASE("without contacts between bodies implicit and explicit response are the same run", "[run]") {
  // cube_drop: one body on the ground plane, no pair that could collide, so no links.
  std::vector<std::vector<std::string>> lines;
  for (const char* mode : {"implicit", "explicit"}) {
    const fs::path dir = fresh_dir(std::string("mode_") + mode);
    RunOptions options;
    options.steps = 200;
    options.out_dir = dir;
    CHECK(run_scene(load_scene_file(resolve_scene("cube_drop", default_scene_dirs()),
                                    {std::string("collision.response=") + mode}),
                    options)
              .status == "ok");
    lines.push_back(lines_of(dir / "steps.csv"));
    fs::remove_all(dir);
  }
  REQUIRE(lines[0].size() == 201);
  REQUIRE(lines[0].size() == lines[1].size());
  for (std::size_t i = 1; i < lines[0].size(); ++i)
    REQUIRE(without_timing(lines[0][0], lines[0][i]) == without_timing(lines[1][0], lines[1][i]));
}

TEST_CASE("full with keep_table is full's run apart from timings and the hashing work", "[run][keep_table]") {
  // plates20 settles into a resting stack: its tets barely leave their
  // cells, so most cycles refresh the kept table. Every column but the
  // timings and the work must be full's, bit for bit.
  const fs::path a = fresh_dir("keep_a"), b = fresh_dir("keep_b");
  const auto path = resolve_scene("plates20", default_scene_dirs());
  for (const auto& dir : {a, b}) {
    const SceneDesc scene = load_scene_file(path, {std::string("method.full.keep_table=") + (dir == a ? "false" : "true")});
    RunOptions options;
    options.method = "full";
    options.steps = 40;
    options.out_dir = dir;
    REQUIRE(run_scene(scene, options).status == "ok");
  }
  const auto la = lines_of(a / "steps.csv"), lb = lines_of(b / "steps.csv");
  REQUIRE(la.size() == 41);
  REQUIRE(la[0] == lb[0]);
  const auto names = cells_of(la[0]);
  const auto is_work = [](const std::string& name) {
    return name == "work_units" || (name.size() > 5 && name.substr(name.size() - 5) == "_work");
  };
  std::uint64_t hash_work[2] = {0, 0};
  const auto hash_column = std::find(names.begin(), names.end(), "stage_hash_tets_work") - names.begin();
  REQUIRE(hash_column < static_cast<std::ptrdiff_t>(names.size()));
  for (std::size_t i = 1; i < la.size(); ++i) {
    const auto ca = cells_of(la[i]), cb = cells_of(lb[i]);
    REQUIRE(ca.size() == names.size());
    for (std::size_t k = 0; k < names.size(); ++k) {
      const std::string& n = names[k];
      if (is_work(n) || (n.size() >= 3 && n.substr(n.size() - 3) == "_ms") || n == "handling_switches") continue;
      INFO("step " << i << " column " << n);
      REQUIRE(ca[k] == cb[k]);
    }
    hash_work[0] += std::stoull(ca[hash_column]);
    hash_work[1] += std::stoull(cb[hash_column]);
  }
  CHECK(hash_work[1] < hash_work[0] / 2);
  const auto ra = nlohmann::json::parse(read_file(a / "run.json"));
  const auto rb = nlohmann::json::parse(read_file(b / "run.json"));
  CHECK(ra["cycles"]["begun"] == 40);
  CHECK(ra["cycles"]["tet_hashes_fresh"] == 40);  // the paper's schedule: every cycle hashes afresh
  CHECK(rb["cycles"]["begun"] == 40);
  CHECK(rb["cycles"]["tet_hashes_fresh"].get<int>() < 10);
  CHECK(rb["settings"]["keep_table"] == true);
  fs::remove_all(a);
  fs::remove_all(b);
}

TEST_CASE("under a work budget two runs are identical apart from timings, whatever the thread count", "[run]") {
  // The paper's task granularity, our fine tasks (resumable hashing), with
  // rehashed stale tets, and our fastest-first order. The second run runs
  // its cycle on 3 threads (collision.threads: hashing, point queries, border
  // depths and forces): the work charged, so where the budget stops, and
  // everything that follows must not change.
  struct Case {
    std::string method;
    bool fine, rehash, keep;
  };
  for (const auto& [method, fine, rehash, keep] : std::vector<Case>{{"interruptible", false, false, false},
                                                                   {"interruptible", true, false, false},
                                                                   {"interruptible", true, true, false},
                                                                   {"interruptible", false, false, true},
                                                                   {"interruptible_prioritized", false, false, false}}) {
  INFO(method << " fine_tasks " << fine << " rehash_stale " << rehash << " keep_table " << keep);
  const fs::path a = fresh_dir("work_a"), b = fresh_dir("work_b");
  const std::vector<std::string> sets = {"method." + method + ".fine_tasks=" + (fine ? "true" : "false"),
                                         "method." + method + ".rehash_stale=" + (rehash ? "true" : "false"),
                                         "method." + method + ".keep_table=" + (keep ? "true" : "false")};
  std::vector<std::string> threaded = sets;
  threaded.push_back("collision.threads=3");
  const auto path = resolve_scene("plates20", default_scene_dirs());
  for (const auto& dir : {a, b}) {
    const SceneDesc scene = load_scene_file(path, dir == a ? sets : threaded);
    RunOptions options;
    options.method = method;
    options.budget = {BudgetKind::Work, 20000};
    options.steps = 60;
    options.out_dir = dir;
    CHECK(run_scene(scene, options).status == "ok");
  }
  const auto la = lines_of(a / "steps.csv"), lb = lines_of(b / "steps.csv");
  REQUIRE(la.size() == 61);
  int interrupted = 0;
  for (std::size_t i = 1; i < la.size(); ++i) {
    REQUIRE(without_timing(la[0], la[i]) == without_timing(lb[0], lb[i]));
    const auto names = cells_of(la[0]);
    const auto column = std::find(names.begin(), names.end(), "cycle_done") - names.begin();
    std::stringstream in(la[i]);
    std::string cell;
    for (std::ptrdiff_t k = 0; k <= column; ++k) std::getline(in, cell, ',');
    interrupted += cell == "0";
  }
  CHECK(interrupted > 10);  // the budget really interrupted cycles
  const auto run = nlohmann::json::parse(read_file(a / "run.json"));
  CHECK(run["budget"]["kind"] == "work");
  CHECK(run["budget"]["value"] == 20000);
  CHECK(run["summary"]["cycle_steps"]["max"].get<double>() > 1.0);
  CHECK(run["settings"]["fine_tasks"] == fine);
  CHECK(run["settings"]["rehash_stale"] == rehash);
  CHECK(run["settings"]["keep_table"] == keep);
  // Cycles that refreshed the last table instead of hashing afresh: only
  // with keep_table (else every cycle hashes, but the last may not have finished).
  const auto fresh = run["cycles"]["tet_hashes_fresh"].get<std::int64_t>(), begun = run["cycles"]["begun"].get<std::int64_t>();
  if (keep) CHECK(begun > 2);  // cycles after the first, to refresh
  CHECK((fresh < begun - 1) == keep);
  CHECK(run["collision"]["threads"] == 1);
  const auto threaded_run = nlohmann::json::parse(read_file(b / "run.json"));
  CHECK(threaded_run["collision"]["threads"] == 3);
  // The vCPUs' handover, probed only where the cycle has threads to split
  // over: at both ends of the run a ratio of two read times, or null where
  // the probe's two threads ran on one CPU (this suite runs tests side by
  // side, so that may happen).
  CHECK(run["collision"]["handover_ratio"].is_null());
  const nlohmann::json& handover = threaded_run["collision"]["handover_ratio"];
  REQUIRE(handover.is_object());
  CHECK(handover.size() == 2);
  for (const char* end : {"start", "end"}) {
    INFO(end);
    REQUIRE(handover.contains(end));
    CHECK((handover[end].is_null() || (handover[end].is_number() && handover[end].get<double>() > 0.0)));
  }
  // The largest charge: the paper's one hashing task, or a small piece of it.
  CHECK((run["summary"]["max_task_work"].get<double>() > 10000.0) == !fine);
  fs::remove_all(a);
  fs::remove_all(b);
  }
}

TEST_CASE("without a budget full handling is the same run on 1 and 2 threads", "[run]") {
  const fs::path a = fresh_dir("threads_1"), b = fresh_dir("threads_2");
  const auto path = resolve_scene("plates20", default_scene_dirs());
  for (const auto& dir : {a, b}) {
    RunOptions options;
    options.method = "full";
    options.steps = 40;
    options.out_dir = dir;
    const SceneDesc scene = load_scene_file(path, {dir == a ? "collision.threads=1" : "collision.threads=2"});
    CHECK(run_scene(scene, options).status == "ok");
  }
  const auto la = lines_of(a / "steps.csv"), lb = lines_of(b / "steps.csv");
  REQUIRE(la.size() == 41);
  for (std::size_t i = 1; i < la.size(); ++i) REQUIRE(without_timing(la[0], la[i]) == without_timing(lb[0], lb[i]));
  const auto run = nlohmann::json::parse(read_file(a / "run.json"));
  CHECK(run["summary"]["colliding_points_max"].get<double>() > 100.0);  // the queries found contacts to agree on
  // The handler's own memory, per tet: more with a second thread's scratch
  // and part lists, and well below the whole process's.
  const auto threaded = nlohmann::json::parse(read_file(b / "run.json"));
  const double one = run["collision_memory"]["bytes_per_tet"].get<double>();
  CHECK(one > 56.0);  // at least a box, an owner and a stamp per tet
  CHECK(threaded["collision_memory"]["bytes_per_tet"].get<double>() > one);
  // The performance issue's ceiling, 1 KB a tet (292 and 419 B here on 1 and
  // 2 threads, 26 B of them the detector's slots; 234 B at 1M tets before
  // the slots, scaling_large.toml): a table, list or scratch that grew with
  // the wrong size fails here first.
  CHECK(threaded["collision_memory"]["bytes_per_tet"].get<double>() < 1024.0);
  CHECK(run["collision_memory"]["tets"] == run["peak_memory"]["tets"]);
  CHECK(one < run["peak_memory"]["bytes_per_tet"].get<double>());
  fs::remove_all(a);
  fs::remove_all(b);
}

TEST_CASE("stage times lie inside handling time, the step is handling plus dynamics", "[run][stages]") {
  const fs::path dir = fresh_dir("stages");
  RunOptions options;
  options.method = "interruptible";
  options.budget = {BudgetKind::Work, 20000};
  options.steps = 30;
  options.out_dir = dir;
  REQUIRE(run_scene(load_scene_file(resolve_scene("plates20", default_scene_dirs())), options).status == "ok");
  const auto lines = lines_of(dir / "steps.csv");
  const auto names = cells_of(lines[0]);
  const auto column = [&](const std::string& name) {
    const auto at = static_cast<std::size_t>(std::find(names.begin(), names.end(), name) - names.begin());
    REQUIRE(at < names.size());
    return at;
  };
  const std::size_t handling = column("handling_ms"), handling_cpu = column("handling_cpu_ms"),
                    dynamics = column("dynamics_ms"), step = column("step_ms"),
                    interrupted = column("interrupted_stage");
  const std::size_t work_units = column("work_units");
  std::vector<std::size_t> stage_work;
  for (const char* s : {"prioritize", "hash_tets", "query_points", "hash_surface", "border_depth", "propagate", "forces"})
    stage_work.push_back(column(std::string("stage_") + s + "_work"));
  std::vector<std::size_t> stages;
  for (const char* s : {"prioritize", "hash_tets", "query_points", "hash_surface", "border_depth", "propagate",
                        "forces", "apply"})
    stages.push_back(column(std::string("stage_") + s + "_ms"));
  int interruptions = 0;
  double stages_total_ms = 0.0, handling_cpu_total_ms = 0.0;
  for (std::size_t l = 1; l < lines.size(); ++l) {
    INFO("step " << l);
    const auto cells = cells_of(lines[l]);
    double sum = 0.0;
    for (std::size_t c : stages) {
      CHECK(std::stod(cells[c]) >= -1e-9);
      sum += std::stod(cells[c]);
    }
    // The stages are read inside the handler, the handling interval around it.
    CHECK(sum <= std::stod(cells[handling]) + 1e-6);
    stages_total_ms += sum;
    handling_cpu_total_ms += std::stod(cells[handling_cpu]);
    std::int64_t work = 0;
    for (std::size_t c : stage_work) work += std::stoll(cells[c]);
    CHECK(work == std::stoll(cells[work_units]));  // exactly
    CHECK(std::stod(cells[step]) == Approx(std::stod(cells[handling]) + std::stod(cells[dynamics])).margin(1e-9));
    if (!cells[interrupted].empty()) {
      ++interruptions;
      CHECK(std::stoi(cells[interrupted]) >= 0);
      CHECK(std::stoi(cells[interrupted]) <= 6);
    }
  }
  CHECK(interruptions > 10);  // 20,000 units are a fraction of plates20's cycle
  // And the stages cover the handling interval, up to the call and a few
  // clock reads: judged over the run, against the thread's CPU time, not the
  // wall time (on a loaded machine the scheduler takes the CPU at the thread
  // clock's system call, inside the handling interval but outside the stages:
  // measured 8 ms of 9 while a sweep ran). A per-step bound of 50 us failed in
  // CI once (a 54 us gap at one step while two compilers shared the cores),
  // so the same 50 us a step is allowed over the run as a whole: one slow
  // step borrows from the others, a stage left untimed on every step does not.
  CHECK(stages_total_ms >= handling_cpu_total_ms - 0.05 * static_cast<double>(lines.size() - 1));
  const auto run = nlohmann::json::parse(read_file(dir / "run.json"));
  const auto& summary = run["summary"];
  REQUIRE(summary["stages"].is_object());
  // The paper's one hashing task charged its tets, the queries their visits.
  CHECK(summary["stages"]["hash_tets"]["work_mean"].get<double>() > 0.0);
  CHECK(summary["stages"]["query_points"]["work_mean"].get<double>() > 0.0);
  CHECK(summary["stages"]["prioritize"]["work_mean"].get<double>() == 0.0);  // index order
  std::int64_t interrupted_steps = 0;
  for (const auto& [name, stage] : summary["stages"].items()) interrupted_steps += stage["interrupted_steps"].get<std::int64_t>();
  CHECK(interrupted_steps == interruptions);
  CHECK(summary["stages_ms_unaccounted_mean"].get<double>() >= -1e-9);

  CHECK(summary["step_ms"]["p50"].get<double>() > summary["handling_ms"]["p50"].get<double>());
  fs::remove_all(dir);
}

TEST_CASE("vertices renumbered along the curve: the same scene, and every file in the mesh file's numbering",
          "[run][mesh_order]") {
  // A cube dropped onto a passive slab, placed off every lattice plane so no
  // vertex lands exactly on a face: then the two numberings differ only in
  // the order of sums, not in a tie-break, and stay close.
  const auto scene_text = [](const std::string& order) {
    return "[scene]\ndt = 0.001\nsteps = 60\nmesh_order = \"" + order + "\"\n" +
           R"([[object]]
name = "slab"
mesh = "box:size=0.3x0.05x0.3,cells=6x1x6"
passive = true
[[object]]
name = "cube"
mesh = "box:size=0.1x0.1x0.1,cells=3x3x3"
position = [0.0123, 0.0771, 0.0071]
velocity = [0.0, -1.0, 0.0]
)";
  };
  const fs::path a = fresh_dir("order_file"), b = fresh_dir("order_curve");
  for (const auto& dir : {a, b}) {
    RunOptions options;
    options.out_dir = dir;
    options.trajectory_every = 10;
    options.record_every = 10;
    options.oracle.every = 10;
    if (dir == b) options.reference_dir = a;  // divergence from the file's run, vertex by vertex
    REQUIRE(run_scene(parse_scene(scene_text(dir == a ? "file" : "curve"), "order.toml"), options).status == "ok");
  }
  const auto ra = nlohmann::json::parse(read_file(a / "run.json")), rb = nlohmann::json::parse(read_file(b / "run.json"));
  CHECK(ra["world"]["mesh_order"] == "file");
  CHECK(rb["world"]["mesh_order"] == "curve");
  // The same contacts step by step (no tie-break is in play), and some: the cube reached the slab.
  const auto colliding = [](const fs::path& dir) {
    const auto lines = lines_of(dir / "steps.csv");
    const auto names = cells_of(lines.at(0));
    const auto column =
        static_cast<std::size_t>(std::find(names.begin(), names.end(), "colliding_points") - names.begin());
    std::vector<std::string> counts;
    for (std::size_t i = 1; i < lines.size(); ++i) counts.push_back(cells_of(lines[i]).at(column));
    return counts;
  };
  const auto ca = colliding(a);
  CHECK(colliding(b) == ca);
  CHECK(std::any_of(ca.begin(), ca.end(), [](const std::string& c) { return c != "0"; }));
  // The first ParaView frame is the rest state: in the file's numbering it
  // is the same file byte for byte.
  CHECK(read_file(a / "frames" / "frame_000000.vtu") == read_file(b / "frames" / "frame_000000.vtu"));
  // trajectory.bin in the file's numbering: vertex for vertex within
  // rounding of the other run (written in the run's own numbering, the same
  // vertex index would be a vertex up to 0.1 m away).
  TrajectoryReader ta(a / "trajectory.bin"), tb(b / "trajectory.bin");
  CHECK(ta.masses_kg() == tb.masses_kg());
  int compared = 0;
  while (auto fa = ta.next()) {
    const auto fb = tb.next();
    REQUIRE(fb);
    REQUIRE(fa->step == fb->step);
    for (std::size_t body = 0; body < fa->x_m.size(); ++body)
      for (std::size_t v = 0; v < fa->x_m[body].size(); ++v)
        REQUIRE((fa->x_m[body][v] - fb->x_m[body][v]).norm() < 1e-6);
    ++compared;
  }
  CHECK(compared == 6);
  // The divergence meter read this run in the file's numbering too.
  CHECK(rb["summary"]["divergence"]["compared_steps"] == 6);
  CHECK(rb["summary"]["divergence"]["max_m"]["max"].get<double>() < 1e-6);
  // The replay, frame by frame: surface positions, the method's contacts and
  // the oracle's inside points, each named by (body, file vertex), agree.
  using Point = std::pair<std::uint32_t, std::uint32_t>;
  struct Frame {
    std::map<Point, Vec3> surface;
    std::set<Point> contacts, oracle;
  };
  const auto replay = [](const fs::path& dir) {
    const auto manifest = nlohmann::json::parse(read_file(dir / "replay.json"));
    const std::string bin = read_file(dir / "replay.bin");
    const auto u32 = [&](std::size_t at) {
      std::uint32_t v = 0;
      std::memcpy(&v, bin.data() + at, 4);
      return v;
    };
    const auto f32 = [&](std::size_t at) {
      float v = 0;
      std::memcpy(&v, bin.data() + at, 4);
      return static_cast<double>(v);
    };
    std::vector<Point> surface_map;
    const auto map_at = manifest["surface_map"]["offset"].get<std::size_t>();
    for (std::size_t i = 0; i < manifest["surface_map"]["count"].get<std::size_t>(); ++i)
      surface_map.emplace_back(u32(map_at + 8 * i), u32(map_at + 8 * i + 4));
    std::vector<Frame> frames;
    for (const auto& f : manifest["frames"]) {
      Frame frame;
      const auto at = f["positions_offset"].get<std::size_t>();
      for (std::size_t i = 0; i < surface_map.size(); ++i)
        frame.surface[surface_map[i]] = Vec3(f32(at + 12 * i), f32(at + 12 * i + 4), f32(at + 12 * i + 8));
      const auto points = [&](const nlohmann::json& block, std::size_t bytes, std::set<Point>& into) {
        for (std::size_t i = 0; i < block["count"].get<std::size_t>(); ++i) {
          const std::size_t p = block["offset"].get<std::size_t>() + bytes * i;
          into.insert({u32(p), u32(p + 4)});
        }
      };
      points(f["contacts"], manifest["layouts"]["contact"]["bytes"].get<std::size_t>(), frame.contacts);
      points(f["oracle"], manifest["layouts"]["oracle_point"]["bytes"].get<std::size_t>(), frame.oracle);
      frames.push_back(std::move(frame));
    }
    return frames;
  };
  const std::vector<Frame> fa = replay(a), fb = replay(b);
  REQUIRE(fa.size() == 6);
  REQUIRE(fb.size() == fa.size());
  for (std::size_t i = 0; i < fa.size(); ++i) {
    REQUIRE(fa[i].surface.size() > 100);
    REQUIRE(fb[i].surface.size() == fa[i].surface.size());
    for (const auto& [point, x] : fa[i].surface) {
      REQUIRE(fb[i].surface.count(point) == 1);
      REQUIRE((fb[i].surface.at(point) - x).norm() < 1e-6);
    }
    CHECK(fb[i].contacts == fa[i].contacts);
    CHECK(fb[i].oracle == fa[i].oracle);
  }
  // The cube rests on the slab in the first frames (steps 10, 20) and has
  // bounced off by the last ones: contacts and inside points to compare.
  CHECK(std::any_of(fa.begin(), fa.end(), [](const Frame& f) { return !f.contacts.empty(); }));
  CHECK(std::any_of(fa.begin(), fa.end(), [](const Frame& f) { return !f.oracle.empty(); }));
  fs::remove_all(a);
  fs::remove_all(b);
}
