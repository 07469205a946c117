// The force reference on real runs: zero for full and for the interruptible
// method without a budget (the shadow is the same computation on the same
// state), positive where forces are held or estimated, split by source, and
// the run itself untouched by its shadow.
#include "experiments/metrics/force_reference_meter.hpp"

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>
#include <unistd.h>

#include <fstream>

#include "experiments/run/run_scene.hpp"
#include "experiments/scene/scene_file.hpp"
#include "sim/io/atomic_file.hpp"

using namespace tcb;
namespace fs = std::filesystem;

namespace {

struct Result {
  nlohmann::json summary;
  std::vector<std::string> kinetic_energy;  // steps.csv, per step
};

Result run(const std::string& method, const std::vector<std::string>& sets, BudgetSpec budget, bool reference,
           std::int64_t steps = 12, std::int64_t every = 1) {
  const fs::path dir = fs::temp_directory_path() / ("tcbench_force_ref_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  RunOptions options;
  options.method = method;
  options.budget = budget;
  options.steps = steps;
  options.out_dir = dir;
  if (reference) options.force_reference = OracleSchedule{every};
  const SceneDesc scene = load_scene_file(resolve_scene("plates20", default_scene_dirs()), sets);
  REQUIRE(run_scene(scene, options).status == "ok");
  Result r;
  r.summary = nlohmann::json::parse(read_file(dir / "run.json"))["summary"];
  std::ifstream in(dir / "steps.csv");
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  {
    std::stringstream header(line);
    for (std::string c; std::getline(header, c, ',');) names.push_back(c);
  }
  const auto column = static_cast<std::size_t>(std::find(names.begin(), names.end(), "kinetic_energy") - names.begin());
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::string cell;
    for (std::size_t k = 0; k <= column; ++k) std::getline(row, cell, ',');
    r.kinetic_energy.push_back(cell);
  }
  fs::remove_all(dir);
  return r;
}

}  // namespace

TEST_CASE("force error is 0 for full and for interruptible without a budget", "[force_error][run]") {
  for (const std::string response : {"implicit", "explicit"}) {
    for (const std::string method : {"full", "interruptible", "interruptible_tracked"}) {
      INFO(method << ", " << response);
      const Result r = run(method, {"collision.response=" + response}, {}, true);
      const auto& e = r.summary["force_error"];
      REQUIRE(e.is_object());
      CHECK(e["samples"] == 12);
      CHECK(e["relative_l2"]["max"].get<double>() == 0.0);
      CHECK(e["missed_share"]["max"].get<double>() == 0.0);
      CHECK(e["ghost_share"]["max"].get<double>() == 0.0);
      CHECK(e["by_source"]["computed"]["points"].get<std::int64_t>() > 0);
      CHECK(e["by_source"]["held"]["points"] == 0);
      CHECK(e["reference_ms_mean"].get<double>() > 0.0);
    }
  }
}

TEST_CASE("force error is positive where forces are held or estimated", "[force_error][run]") {
  for (const std::string response : {"implicit", "explicit"}) {
    INFO(response);
    // every_nth n=2 holds the last cycle's forces on every other step while the stack settles.
    const Result nth = run("every_nth", {"collision.response=" + response, "method.every_nth.n=2"}, {}, true);
    const auto& e = nth.summary["force_error"];
    CHECK(e["relative_l2"]["max"].get<double>() > 0.0);
    CHECK(e["by_source"]["held"]["points"].get<std::int64_t>() > 0);
    CHECK(e["by_source"]["computed"]["points"].get<std::int64_t>() > 0);
    // The paper's method under a work budget: cycles span steps, forces are extrapolated.
    const Result paper = run("interruptible", {"collision.response=" + response}, {BudgetKind::Work, 60000}, true, 20);
    const auto& p = paper.summary["force_error"];
    CHECK(p["relative_l2"]["max"].get<double>() > 0.0);
    CHECK(p["by_source"]["extrapolated"]["points"].get<std::int64_t>() +
              p["by_source"]["held"]["points"].get<std::int64_t>() >
          0);
  }
}

TEST_CASE("the force reference leaves the run unchanged", "[force_error][run]") {
  const Result with = run("interruptible", {}, {BudgetKind::Work, 60000}, true, 20);
  const Result without = run("interruptible", {}, {BudgetKind::Work, 60000}, false, 20);
  CHECK(with.kinetic_energy == without.kinetic_energy);
  CHECK(without.summary["force_error"].is_null());
}

TEST_CASE("force reference samples one step in K, in rotating phase", "[force_error]") {
  const OracleSchedule ten{10};
  std::vector<std::int64_t> sampled;
  for (std::int64_t s = 1; s <= 120; ++s)
    if (force_reference_due(ten, s)) sampled.push_back(s);
  CHECK(sampled == std::vector<std::int64_t>{11, 22, 33, 44, 55, 66, 77, 88, 99, 100, 111});
  for (std::int64_t s = 1; s <= 5; ++s) CHECK(force_reference_due(OracleSchedule{1}, s));
  CHECK_FALSE(force_reference_due(OracleSchedule{0}, 10));
  // every_nth n=2 under every:2 is seen computing and holding, not in one phase only.
  const Result nth = run("every_nth", {"method.every_nth.n=2"}, {}, true, 16, 2);
  CHECK(nth.summary["force_error"]["by_source"]["computed"]["points"].get<std::int64_t>() > 0);
  CHECK(nth.summary["force_error"]["by_source"]["held"]["points"].get<std::int64_t>() > 0);
}
