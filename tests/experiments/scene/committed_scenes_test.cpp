// Every committed scene (experiments/scenes/*.toml) loads and runs a few steps
// with full; the haptic probe reports a force once it touches the cow.
#include <catch2/catch.hpp>

#include "experiments/run/provenance.hpp"
#include "experiments/run/run_scene.hpp"
#include "experiments/scene/scene_file.hpp"
#include "sim/io/atomic_file.hpp"

#include <nlohmann/json.hpp>
#include <algorithm>
#include <unistd.h>

using namespace tcb;
namespace fs = std::filesystem;

TEST_CASE("every committed scene loads and runs", "[scene]") {
  std::vector<fs::path> files;  // whatever experiments/scenes/ holds: a new scene is tested without editing this
  for (const auto& entry : fs::directory_iterator(source_tree_dir() / "experiments" / "scenes"))
    if (entry.path().extension() == ".toml") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  REQUIRE(files.size() >= 6);  // the paper's scenes and cube_drop, at least
  for (const fs::path& file : files) {
    const std::string name = file.stem().string();
    INFO(name);
    const SceneDesc scene = load_scene_file(file);
    RunOptions options;
    options.steps = 5;
    options.out_dir = fs::temp_directory_path() / ("tcbench_scene_" + std::string(name) + std::to_string(::getpid()));
    CHECK(run_scene(scene, options).status == "ok");
    fs::remove_all(options.out_dir);
  }
}

TEST_CASE("haptic_probe: the probe presses the cow and the force the device renders points back up", "[scene][slow]") {
  const SceneDesc scene = load_scene_file(resolve_scene("haptic_probe", default_scene_dirs()));
  RunOptions options;
  options.steps = 420;  // into the press (starts at 0.1 s, 5.5 cm down by 0.4 s)
  options.out_dir = fs::temp_directory_path() / ("tcbench_haptic_" + std::to_string(::getpid()));
  REQUIRE(run_scene(scene, options).status == "ok");
  const auto run = nlohmann::json::parse(read_file(options.out_dir / "run.json"));
  CHECK(run["summary"]["probe_force_max"].get<double>() > 1.0);
  std::ifstream csv(options.out_dir / "steps.csv");
  std::string header, line, last;
  std::getline(csv, header);
  while (std::getline(csv, line)) last = line;
  std::vector<std::string> names, cells;
  std::stringstream h(header), l(last);
  for (std::string c; std::getline(h, c, ',');) names.push_back(c);
  for (std::string c; std::getline(l, c, ',');) cells.push_back(c);
  const auto y = std::find(names.begin(), names.end(), "probe_force_y") - names.begin();
  CHECK(std::stod(cells[y]) > 0.0);  // the cow pushes the probe up
  fs::remove_all(options.out_dir);
}

TEST_CASE("finger_curl: the oracle judges neural and full per frame; neural has no point metrics", "[scene][neural]") {
  const SceneDesc scene = load_scene_file(resolve_scene("finger_curl", default_scene_dirs()));
  const auto summary_of = [&](const std::string& method) {
    RunOptions options;
    options.method = method;
    options.steps = 600;  // through the first curl (self-collision from about 0.3 s)
    options.oracle.every = 10;
    options.out_dir = fs::temp_directory_path() / ("tcbench_finger_" + method + std::to_string(::getpid()));
    REQUIRE(run_scene(scene, options).status == "ok");
    const auto run = nlohmann::json::parse(read_file(options.out_dir / "run.json"));
    fs::remove_all(options.out_dir);
    return run["summary"];
  };
  const auto full = summary_of("full");
  const auto neural = summary_of("neural");
  INFO("full " << full["self_frames"].dump() << "; neural " << neural["self_frames"].dump());
  REQUIRE(full["self_frames"].is_object());
  CHECK(full["self_frames"]["frames"] == 60);
  CHECK(full["self_frames"]["tp"].get<int>() > 0);   // the path does fold the finger
  CHECK(full["self_frames"]["tn"].get<int>() > 0);   // and not all the time
  CHECK(full["self_frames"]["accuracy"] == 1.0);     // full detection is exact here
  CHECK(full["recall_min"] == 1.0);
  // Per part (7 bones): full holds a point in every part the oracle finds one in, and in no other.
  REQUIRE(full["self_parts"].is_object());
  CHECK(full["self_parts"]["judged"] == 60 * 7);
  CHECK(full["self_parts"]["tp"].get<int>() > 0);
  CHECK(full["self_parts"]["recall"] == 1.0);
  CHECK(full["self_parts"]["precision"] == 1.0);
  CHECK(neural["self_parts"].is_null());
  REQUIRE(neural["self_frames"].is_object());
  CHECK(neural["self_frames"]["frames"] == 60);
  CHECK(neural["self_frames"]["accuracy"].get<double>() >= 0.8);  // a learned approximation; 0.94 over the whole path
  CHECK(neural["recall_min"].is_null());
  CHECK(neural["precision_min"].is_null());
  CHECK(neural["work_units_total"] == 600);  // one evaluation per step
  const std::string reasons = neural["oracle_unmeasured"].dump();
  CHECK_THAT(reasons, Catch::Matchers::Contains("whole-object verdicts"));
}
