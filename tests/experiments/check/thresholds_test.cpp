#include "experiments/check/thresholds.hpp"

#include <catch2/catch.hpp>

#include <unistd.h>

#include <list>

#include <nlohmann/json.hpp>

#include "experiments/cli/cli.hpp"
#include "sim/io/atomic_file.hpp"
#include "tests/remove_on_exit.hpp"
#include "sim/io/input_error.hpp"

using namespace tcb;
namespace fs = std::filesystem;

namespace {

// A run directory as check reads it: run.json, and a steps.csv that agrees
// with it (a run counts as complete only then: summary_csv.hpp).
void write_run(const fs::path& dir, nlohmann::json j) {
  if (!j.contains("steps")) j["steps"] = 0;
  fs::create_directories(dir);
  write_file_atomically(dir / "run.json", j.dump());
  std::string csv = "step,time_s\n";
  for (std::int64_t s = 1; s <= j["steps"].get<std::int64_t>(); ++s) csv += std::to_string(s) + ",0\n";
  write_file_atomically(dir / "steps.csv", csv);
}

// A results directory with two runs, run.json files written by hand: this
// tests check, not the runs.
fs::path fixture() {
  const fs::path dir = fs::temp_directory_path() / ("tcbench_check_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const auto run = [&](const std::string& name, const std::string& method, const std::string& budget, double recall,
                       const std::string& label = "") {
    nlohmann::json j;
    j["scene"] = "plates20";
    j["method"] = method;
    j["method_label"] = label.empty() ? method : label;
    j["budget"] = {{"kind", "work"}, {"value", 100}, {"label", budget}};
    j["seed"] = 0;
    j["status"] = "ok";
    j["summary"] = {{"recall_min", recall}, {"depth_err", {{"max", 0.002}}}, {"jitter", nullptr}};
    write_run(dir / "runs" / name, j);
  };
  run("a", "full", "none", 1.0);
  run("b", "interruptible", "work:100", 0.8);
  run("c", "every_nth", "none", 0.5, "every_nth(n=3)");
  run("d", "every_nth", "none", 0.7);
  return dir;
}

fs::path thresholds_path() {
  return fs::temp_directory_path() / ("tcbench_thresholds_" + std::to_string(::getpid()) + ".toml");
}

fs::path thresholds(const std::string& text) {
  write_file_atomically(thresholds_path(), text);
  return thresholds_path();
}


int cli(const std::vector<std::string>& args) {
  std::vector<const char*> argv{"tcbench"};
  for (const auto& a : args) argv.push_back(a.c_str());
  return run_cli(static_cast<int>(argv.size()), argv.data());
}

}  // namespace

TEST_CASE("check passes, fails and reports missing runs and metrics", "[check]") {
  const test::RemoveOnExit cleanup{thresholds_path()};  // passed or failed
  const fs::path dir = fixture();
  const fs::path pass = thresholds(R"([[threshold]]
scene = "plates20"
method = "full"
metric = "recall_min"
min = 1.0

[[threshold]]
scene = "plates20"
method = "full"
metric = "depth_err.max"
max = 0.01
)");
  CHECK(cli({"check", pass.string(), dir.string()}) == 0);

  const std::vector<Threshold> t = load_thresholds(thresholds(R"([[threshold]]
scene = "plates20"
method = "interruptible"
budget = "work:100"
metric = "recall_min"
min = 0.9

[[threshold]]
scene = "plates20"
method = "full"
metric = "jitter"
max = 1.0

[[threshold]]
scene = "cube_drop"
method = "full"
metric = "recall_min"
min = 0.0

[[threshold]]
scene = "plates20"
method = "full"
metric = "recal_min"
min = 0.0
)"));
  const std::vector<CheckRow> rows = check_thresholds(t, dir);
  REQUIRE(rows.size() == 4);
  CHECK(rows[0].verdict == "FAIL");  // 0.8 < 0.9
  CHECK(*rows[0].value == 0.8);
  CHECK(rows[1].verdict == "missing");  // null: nothing measured must not pass
  CHECK(rows[2].verdict == "missing");  // no such run
  CHECK(rows[3].verdict == "unknown metric");  // a misspelling, not a figure that was not measured (issue 15, defect 7)
  CHECK(cli({"check", thresholds_path().string(), dir.string()}) == 1);
  // A method's label tells runs with other settings apart.
  const std::vector<CheckRow> nth = check_thresholds(load_thresholds(thresholds(R"toml([[threshold]]
scene = "plates20"
method = "every_nth(n=3)"
metric = "recall_min"
min = 0.5

[[threshold]]
scene = "plates20"
method = "every_nth"
metric = "recall_min"
min = 0.7
)toml")),
                                                     dir);
  REQUIRE(nth.size() == 2);
  CHECK(nth[0].run == "runs/c");  // named by its path below DIR
  CHECK(nth[1].run == "runs/d");
  // reproduce's layout, DIR/<sweep>/runs/<id>: found at any depth; reports are not searched.
  fs::create_directories(dir / "1_stack" / "runs");
  fs::rename(dir / "runs" / "c", dir / "1_stack" / "runs" / "c");
  fs::create_directories(dir / "report" / "x");
  write_run(dir / "report" / "x", nlohmann::json::parse(read_file(dir / "1_stack" / "runs" / "c" / "run.json")));
  const auto deep = check_thresholds(load_thresholds(thresholds(R"toml([[threshold]]
scene = "plates20"
method = "every_nth(n=3)"
metric = "recall_min"
min = 0.5
)toml")),
                                     dir);
  REQUIRE(deep.size() == 1);
  CHECK(deep[0].run == "1_stack/runs/c");
  fs::remove_all(dir);
}

TEST_CASE("check filters by response mode and bounds ratios to a reference run", "[check]") {
  const test::RemoveOnExit cleanup{thresholds_path()};  // passed or failed
  const fs::path dir = fs::temp_directory_path() / ("tcbench_check_rel_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const auto run = [&](const std::string& name, const std::string& method, const std::string& budget,
                       const std::string& response, double jitter, std::vector<std::string> overrides = {}) {
    nlohmann::json j;
    j["scene"] = "plates20";
    j["method"] = j["method_label"] = method;
    j["budget"] = {{"label", budget}};
    j["seed"] = 0;
    j["response"] = response;
    j["overrides"] = overrides;
    j["status"] = "ok";
    j["summary"] = {{"jitter", jitter}};
    write_run(dir / name, j);
  };
  run("full_implicit", "full", "none", "implicit", 0.02);
  // Another sweep's full of the same scene (it sorts first): never the reference of a run elsewhere.
  run("a_sweep/full", "full", "none", "implicit", 0.5);
  run("full_explicit", "full", "none", "explicit", 0.01, {"collision.response=explicit"});
  run("tracked_implicit", "interruptible_tracked", "full-work/3", "implicit", 0.03);
  run("tracked_explicit", "interruptible_tracked", "full-work/3", "explicit", 0.05, {"collision.response=explicit"});
  run("lonely", "interruptible", "full-work/3", "implicit", 0.03, {"scene.dt=0.002"});  // no full with that set
  const auto rows = check_thresholds(load_thresholds(thresholds(R"toml([[threshold]]
scene = "plates20"
method = "interruptible_tracked"
budget = "full-work/3"
response = "implicit"
metric = "jitter"
relative_to = "full"
max = 2.0

[[threshold]]
scene = "plates20"
method = "interruptible_tracked"
budget = "full-work/3"
metric = "jitter"
relative_to = "full"
max = 2.0

[[threshold]]
scene = "plates20"
method = "interruptible"
budget = "full-work/3"
metric = "jitter"
relative_to = "full"
max = 2.0
)toml")),
                                     dir);
  REQUIRE(rows.size() == 4);
  CHECK(rows[0].run == "tracked_implicit");  // the explicit run is left out
  CHECK(rows[0].reference == "full_implicit");
  CHECK(*rows[0].value == Approx(1.5));
  CHECK(rows[0].verdict == "pass");
  CHECK(rows[1].run == "tracked_explicit");  // without response: both modes, each against its own full
  CHECK(rows[1].reference == "full_explicit");
  CHECK(*rows[1].value == Approx(5.0));
  CHECK(rows[1].verdict == "FAIL");
  CHECK(rows[2].run == "tracked_implicit");
  CHECK(rows[3].run == "lonely");  // no reference with its overrides: nothing measured must not pass
  CHECK(rows[3].verdict == "missing");
  fs::remove_all(dir);
}

TEST_CASE("a wall-clock threshold on a noisy run is inconclusive: exit 4, or 1 with --strict-timing", "[check]") {
  const test::RemoveOnExit cleanup{thresholds_path()};  // passed or failed
  const fs::path dir = fs::temp_directory_path() / ("tcbench_check_noisy_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const auto run = [&](const std::string& name, const std::string& kind, const std::string& verdict,
                       double overshoot_p99 = 4.0) {
    nlohmann::json j;
    j["scene"] = "plates20";
    j["method"] = j["method_label"] = "interruptible";
    j["budget"] = {{"kind", kind}, {"label", kind == "wall_ms" ? "ms:3.5" : "work:100"}};
    j["seed"] = 0;
    j["status"] = "ok";
    j["summary"] = {{"recall_min", 0.9},
                    {"overshoot_pct", {{"p99", overshoot_p99}}},
                    {"overshoot_cpu_pct", {{"p99", 1.0}}},
                    {"timing", {{"verdict", verdict}}}};
    write_run(dir / name, j);
  };
  run("wall", "wall_ms", "noisy");
  run("work", "work", "noisy");
  const auto file = thresholds(R"toml([[threshold]]
scene = "plates20"
method = "interruptible"
budget = "ms:3.5"
metric = "overshoot_pct.p99"
max = 5.0

[[threshold]]
scene = "plates20"
method = "interruptible"
budget = "ms:3.5"
metric = "overshoot_cpu_pct.p99"
max = 5.0

[[threshold]]
scene = "plates20"
method = "interruptible"
budget = "work:100"
metric = "recall_min"
min = 0.5
)toml");
  const std::vector<Threshold> t = load_thresholds(file);
  const auto rows = check_thresholds(t, dir);
  REQUIRE(rows.size() == 3);
  CHECK(rows[0].verdict == "inconclusive");  // a wall budget on a noisy machine: the scheduler's number too
  CHECK(rows[1].verdict == "pass");          // CPU time is the method's own
  CHECK(rows[2].verdict == "pass");          // a work budget does not depend on the clock
  CHECK(check_exit_status(rows, false) == 4);
  CHECK(check_exit_status(rows, true) == 1);
  CHECK(cli({"check", file.string(), dir.string()}) == 4);
  CHECK(cli({"check", "--strict-timing", file.string(), dir.string()}) == 1);
  // The same run measured quiet: an ordinary pass; a failing one still fails.
  run("wall", "wall_ms", "quiet");
  CHECK(cli({"check", file.string(), dir.string()}) == 0);
  run("wall", "wall_ms", "quiet", 6.0);
  CHECK(cli({"check", file.string(), dir.string()}) == 1);
  fs::remove_all(dir);
}

TEST_CASE("check rejects malformed thresholds files with exit 2, naming file and line", "[check]") {
  const test::RemoveOnExit cleanup{thresholds_path()};  // passed or failed
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"[[threshold]]\nscene = \"plates20\"\nmethod = \"full\"\nmetric = \"recall_min\"\n", ":1: threshold: give min"},
      {"[[threshold]]\nscene = \"plates20\"\nmethod = \"full\"\nmetric = \"recall_min\"\nmin = \"high\"\n", ":5: threshold.min"},
      {"[[threshold]]\nscene = \"plates20\"\nmetric = \"recall_min\"\nmin = 1\n", ":1: threshold: 'method' is required"},
      {"[[threshold]]\nscene = \"plates20\"\nmethod = \"full\"\nmetric = \"x\"\nmin = 1\nbound = 2\n", ":6: unknown key"},
      {"[[threshold]\n", ":1:"},
      {"[[threshold]]\nscene = \"plates20\"\nmethod = \"full\"\nmetric = \"x\"\nmax = 1\nresponse = \"soft\"\n",
       ":6: threshold.response"},
      {"title = 1\n", ":1: unknown key"},
  };
  for (const auto& [text, expected] : cases) {
    INFO(text);
    const fs::path path = thresholds(text);
    try {
      load_thresholds(path);
      FAIL("accepted");
    } catch (const InputError& e) {
      CHECK_THAT(std::string(e.what()), Catch::Matchers::Contains(path.string() + expected));
    }
    CHECK(cli({"check", path.string(), "."}) == 2);
  }
}

TEST_CASE("check: a threshold may state a run's status and reason, and pick runs by their --set overrides",
          "[check]") {
  const test::RemoveOnExit cleanup{thresholds_path()};  // passed or failed
  const fs::path dir = fs::temp_directory_path() / ("tcbench_check_status_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const auto run = [&](const std::string& name, const std::vector<std::string>& sets, const std::string& status,
                       const std::string& reason, double gain) {
    nlohmann::json j;
    j["scene"] = "two_blocks";
    j["method"] = j["method_label"] = "full";
    j["budget"] = {{"kind", "none"}, {"value", nullptr}, {"label", "none"}};
    j["seed"] = 0;
    j["overrides"] = sets;
    j["status"] = status;
    j["unstable_reason"] = reason.empty() ? nlohmann::json() : nlohmann::json(reason);
    j["summary"] = {{"motion_energy_gain", gain}};
    write_run(dir / "runs" / name, j);
  };
  run("plain", {}, "ok", "", 0.0);
  run("soft", {"b=2", "a=1"}, "unstable", "energy rose by 13 J at step 148", 4.4);
  std::list<std::vector<Threshold>> kept;  // rows point into their thresholds
  const auto check = [&](const std::string& text) {
    kept.push_back(load_thresholds(thresholds(text)));
    return check_thresholds(kept.back(), dir);
  };
  const std::string head = "[[threshold]]\nscene = \"two_blocks\"\nmethod = \"full\"\n";

  // Overrides match in any order; [] is the run without any.
  auto rows = check(head + "set = [\"a=1\", \"b=2\"]\nstatus = \"unstable\"\nreason = \"energy rose\"\n");
  REQUIRE(rows.size() == 1);
  CHECK(rows[0].run == "runs/soft");
  CHECK(rows[0].verdict == "pass");
  CHECK(rows[0].status_check);
  rows = check(head + "set = []\nstatus = \"ok\"\nmetric = \"motion_energy_gain\"\nmax = 0.5\n");
  REQUIRE(rows.size() == 1);
  CHECK(rows[0].run == "runs/plain");
  CHECK(rows[0].verdict == "pass");
  CHECK_FALSE(rows[0].status_check);  // the status held; the metric decided

  // The wrong status, or the right status for another reason, fails; so does
  // a metric out of bounds once the status holds.
  CHECK(check(head + "set = [\"a=1\", \"b=2\"]\nstatus = \"ok\"\nmetric = \"motion_energy_gain\"\nmax = 0.5\n")[0]
            .verdict == "FAIL");
  CHECK(check(head + "set = [\"a=1\", \"b=2\"]\nstatus = \"unstable\"\nreason = \"max_speed\"\n")[0].verdict == "FAIL");
  CHECK(check(head + "set = []\nstatus = \"ok\"\nmetric = \"motion_energy_gain\"\nmax = -1\n")[0].verdict == "FAIL");
  // A set no run has is missing, not passed.
  CHECK(check(head + "set = [\"c=3\"]\nstatus = \"ok\"\n")[0].verdict == "missing");
  // Without set, every run of the scene and method must hold it.
  rows = check(head + "status = \"ok\"\n");
  REQUIRE(rows.size() == 2);
  CHECK(rows[0].verdict != rows[1].verdict);
  const std::string printed = format_check_rows(rows, "t.toml");
  CHECK(printed.find("status") != std::string::npos);
  CHECK(printed.find("unstable") != std::string::npos);

  // Malformed: an unknown status, a reason without status "unstable", bounds without a metric.
  CHECK_THROWS_AS(check(head + "status = \"exploded\"\n"), InputError);
  CHECK_THROWS_AS(check(head + "status = \"ok\"\nreason = \"x\"\n"), InputError);
  CHECK_THROWS_AS(check(head + "status = \"ok\"\nmax = 1\n"), InputError);
  CHECK_THROWS_AS(check(head + "metric = \"motion_energy_gain\"\n"), InputError);  // no bound
  fs::remove_all(dir);
}
