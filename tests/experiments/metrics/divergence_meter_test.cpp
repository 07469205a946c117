// Divergence from a reference run, end to end: a run against its own
// trajectory is 0; held forces and a 1e-9 m perturbation diverge; a
// reference of another scene is refused before the run starts.
#include "experiments/metrics/divergence_meter.hpp"

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>
#include <unistd.h>

#include "experiments/run/run_scene.hpp"
#include "experiments/scene/scene_file.hpp"
#include "sim/io/atomic_file.hpp"
#include "sim/io/input_error.hpp"

using namespace tcb;
namespace fs = std::filesystem;

namespace {

fs::path dir_of(const std::string& name) {
  return fs::temp_directory_path() / ("tcbench_divergence_" + name + "_" + std::to_string(::getpid()));
}

nlohmann::json run(const std::string& scene, const std::string& method, const std::vector<std::string>& sets,
                   const fs::path& out, int trajectory, const fs::path& reference, std::int64_t steps = 40) {
  fs::remove_all(out);
  RunOptions options;
  options.method = method;
  options.steps = steps;
  options.out_dir = out;
  options.trajectory_every = trajectory;
  options.reference_dir = reference;
  REQUIRE(run_scene(load_scene_file(resolve_scene(scene, default_scene_dirs()), sets), options).status == "ok");
  return nlohmann::json::parse(read_file(out / "run.json"));
}

}  // namespace

TEST_CASE("divergence: 0 against itself, positive for held forces and for a 1e-9 m perturbation", "[divergence][run]") {
  const fs::path reference = dir_of("reference"), other = dir_of("other");
  const auto ref = run("plates20", "full", {}, reference, 5, {});
  CHECK(fs::exists(reference / "trajectory.bin"));
  CHECK(ref["trajectory"]["every"] == 5);
  CHECK(ref["summary"]["divergence"].is_null());

  const auto same = run("plates20", "full", {}, other, 0, reference);
  const auto& d = same["summary"]["divergence"];
  CHECK(d["compared_steps"] == 8);
  CHECK(d["last_step"] == 40);
  for (const char* key : {"rms_m", "max_m", "com_drift_m", "orientation_drift_deg", "linear_momentum_diff_n_s",
                          "angular_momentum_diff_n_m_s"})
    CHECK(d[key]["max"].get<double>() == 0.0);

  const auto held = run("plates20", "every_nth", {"method.every_nth.n=3"}, other, 0, reference);
  CHECK(held["summary"]["divergence"]["rms_m"]["max"].get<double>() > 0.0);
  CHECK(held["summary"]["divergence"]["linear_momentum_diff_n_s"]["max"].get<double>() > 0.0);

  const auto floor = run("plates20", "full", {"perturb.position=1e-9"}, other, 0, reference);
  CHECK(floor["perturbation"]["jitter"]["position_m"] == 1e-9);
  CHECK(floor["summary"]["divergence"]["max_m"]["final"].get<double>() > 0.0);

  // A reference of another scene: refused before the run directory exists.
  fs::remove_all(other);
  RunOptions options;
  options.steps = 3;
  options.out_dir = other;
  options.reference_dir = reference;
  CHECK_THROWS_AS(run_scene(load_scene_file(resolve_scene("cube_drop", default_scene_dirs())), options), InputError);
  CHECK_FALSE(fs::exists(other / "run.json"));
  fs::remove_all(reference);
  fs::remove_all(other);
}
