// The command line end to end, in-process: exit codes, help, files.
#include "experiments/cli/cli.hpp"

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <sstream>
#include <vector>

#include "sim/io/atomic_file.hpp"

namespace fs = std::filesystem;

namespace {

struct Result {
  int code;
  std::string out, err;
};

Result cli(std::vector<std::string> args) {
  args.insert(args.begin(), "tcbench");
  std::vector<const char*> argv;
  for (const auto& a : args) argv.push_back(a.c_str());
  std::ostringstream out, err;
  auto* old_out = std::cout.rdbuf(out.rdbuf());
  auto* old_err = std::cerr.rdbuf(err.rdbuf());
  const int code = tcb::run_cli(static_cast<int>(argv.size()), argv.data());
  std::cout.rdbuf(old_out);
  std::cerr.rdbuf(old_err);
  return {code, out.str(), err.str()};
}

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("tcbench_cli_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  return dir;
}

}  // namespace

TEST_CASE("cli: help and version on every subcommand", "[cli]") {
  CHECK(cli({"--help"}).code == 0);
  CHECK_THAT(cli({"--version"}).out, Catch::Matchers::Contains("tcbench 0.1.0"));
  for (const char* sub : {"run", "reproduce", "list", "mesh"}) {
    INFO(sub);
    const Result r = cli({sub, "--help"});
    CHECK(r.code == 0);
    CHECK_FALSE(r.out.empty());
  }
  CHECK(cli({"mesh", "info", "--help"}).code == 0);
  CHECK(cli({}).code == 2);
  CHECK(cli({"frobnicate"}).code == 2);
}

TEST_CASE("cli: run exit codes 0, 1 and 2", "[cli]") {
  const fs::path dir = fresh_dir("run");
  const Result ok = cli({"run", "cube_drop", "--steps", "20", "--out", dir.string(), "--quiet"});
  CHECK(ok.code == 0);
  CHECK(ok.out.empty());
  CHECK(fs::exists(dir / "run.json"));
  CHECK(nlohmann::json::parse(tcb::read_file(dir / "run.json"))["steps"] == 20);

  const Result unstable = cli({"run", "cube_drop", "--set", "object.cube.material.model=mass_spring", "--set",
                               "scene.dt=0.05", "--out", (dir / "boom").string()});
  CHECK(unstable.code == 1);
  CHECK_THAT(unstable.err, Catch::Matchers::Contains("unstable"));
  CHECK(fs::exists(dir / "boom" / "run.json"));

  const Result bad = cli({"run", "cube_drop", "--set", "scene.dt=-1", "--out", (dir / "bad").string()});
  CHECK(bad.code == 2);
  CHECK_THAT(bad.err, Catch::Matchers::Contains("--set scene.dt=-1: scene.dt: must be positive"));
  CHECK_FALSE(fs::exists(dir / "bad"));
  CHECK(cli({"run"}).code == 2);
  CHECK(cli({"run", "plates20", "--budget-ms", "5", "--budget-work", "100"}).code == 2);  // one budget at most
  CHECK(cli({"run", "plates20", "--budget-ms", "-1"}).code == 2);
  const Result wall = cli({"run", "plates20", "--method", "interruptible", "--budget-ms", "2", "--steps", "5",
                           "--out", (dir / "wall").string(), "--quiet"});
  CHECK(wall.code == 0);
  const auto wall_run = nlohmann::json::parse(tcb::read_file(dir / "wall" / "run.json"));
  CHECK(wall_run["budget"]["kind"] == "wall_ms");
  CHECK(wall_run["summary"]["overshoot_pct"]["p99"].is_number());
  // Method settings go through --set like scene keys, and are validated.
  CHECK(cli({"run", "plates20", "--method", "every_nth", "--set", "method.every_nth.n=3", "--steps", "4", "--out",
             (dir / "nth").string(), "--quiet", "--seed", "5"})
            .code == 0);
  // run.json keeps the settings as their own object and the command line as given.
  const auto nth = nlohmann::json::parse(tcb::read_file(dir / "nth" / "run.json"));
  CHECK(nth["settings"]["n"] == 3);
  CHECK(nth["settings"]["hold"] == true);
  CHECK(nth["method_label"] == "every_nth(n=3)");
  CHECK(nth["overrides"].empty());  // a method setting is not a scene override
  const std::vector<std::string> argv = nth["command"];
  CHECK(std::find(argv.begin(), argv.end(), "--seed") != argv.end());
  CHECK(std::find(argv.begin(), argv.end(), "--out") != argv.end());
  CHECK(std::find(argv.begin(), argv.end(), "method.every_nth.n=3") != argv.end());
  const Result bad_n = cli({"run", "plates20", "--method", "every_nth", "--set", "method.every_nth.n=0", "--steps",
                            "4", "--out", (dir / "nth0").string()});
  CHECK(bad_n.code == 2);
  CHECK_THAT(bad_n.err, Catch::Matchers::Contains("--set method.every_nth.n=0"));
  CHECK_FALSE(fs::exists(dir / "nth0"));
  CHECK(cli({"run", "cube_drop", "--steps", "-3"}).code == 2);
  fs::remove_all(dir);
}

TEST_CASE("cli: a run into an earlier run's directory leaves none of the earlier run's files", "[cli]") {
  // Without --record and --trajectory the second run writes no frames, replay
  // or trajectory; the first run's would otherwise pass for its own, to
  // --reference and to tcbench view.
  const fs::path dir = fresh_dir("rerun");
  REQUIRE(cli({"run", "cube_drop", "--steps", "4", "--record", "2", "--trajectory", "2", "--out", dir.string(),
               "--quiet"})
              .code == 0);
  for (const char* name : {"replay.json", "replay.bin", "frames.pvd", "frames", "trajectory.bin"})
    REQUIRE(fs::exists(dir / name));
  tcb::write_file_atomically(dir / "log.txt", "a sweep's log of this run\n");
  tcb::write_file_atomically(dir / "probe_path.csv", "time_s,x_m,y_m,z_m\n");  // live's, an input of replays
  REQUIRE(cli({"run", "cube_drop", "--steps", "2", "--out", dir.string(), "--quiet"}).code == 0);
  for (const char* name : {"replay.json", "replay.bin", "frames.pvd", "frames", "trajectory.bin"}) {
    INFO(name);
    CHECK_FALSE(fs::exists(dir / name));
  }
  CHECK(nlohmann::json::parse(tcb::read_file(dir / "run.json"))["steps"] == 2);
  CHECK(fs::exists(dir / "log.txt"));  // not a run's files
  CHECK(fs::exists(dir / "probe_path.csv"));
  // A folder that holds no run's file is not cleaned: its frames/ is the user's.
  const fs::path mine = dir / "mine";
  fs::create_directories(mine / "frames");
  tcb::write_file_atomically(mine / "frames" / "frame_000001.vtu", "the user's\n");
  REQUIRE(cli({"run", "cube_drop", "--steps", "2", "--out", mine.string(), "--quiet"}).code == 0);
  CHECK(fs::exists(mine / "frames" / "frame_000001.vtu"));
  // In a run's folder only the frames go, not what else the folder holds.
  tcb::write_file_atomically(mine / "frames" / "notes.txt", "kept\n");
  REQUIRE(cli({"run", "cube_drop", "--steps", "2", "--out", mine.string(), "--quiet"}).code == 0);
  CHECK_FALSE(fs::exists(mine / "frames" / "frame_000001.vtu"));
  CHECK(fs::exists(mine / "frames" / "notes.txt"));
  // Nor may a run take its own directory as the reference it replaces.
  REQUIRE(cli({"run", "cube_drop", "--steps", "2", "--trajectory", "1", "--out", dir.string(), "--quiet"}).code == 0);
  const Result same = cli({"run", "cube_drop", "--steps", "2", "--reference", dir.string(), "--out", dir.string()});
  CHECK(same.code == 2);
  CHECK_THAT(same.err, Catch::Matchers::Contains("--reference: is the --out directory"));
  CHECK(fs::exists(dir / "trajectory.bin"));
  fs::remove_all(dir);
}

TEST_CASE("cli: mesh info and convert", "[cli]") {
  const fs::path dir = fresh_dir("mesh");
  fs::create_directories(dir);
  const Result info = cli({"mesh", "info", std::string(TCBENCH_SHARED_MESHES) + "/teapot_tet.mesh", "--json"});
  REQUIRE(info.code == 0);
  const auto j = nlohmann::json::parse(info.out);
  CHECK(j["vertices"] == 4650);
  CHECK(j["tets"] == 15412);
  for (const char* key : {"surface_triangles", "volume", "bbox_min", "bbox_max", "inverted_tets", "degenerate_tets"})
    CHECK(j.contains(key));
  CHECK(cli({"mesh", "info", "box:size=1x1x1,cells=2x2x2"}).code == 0);
  const Result converted = cli({"mesh", "convert", "box:size=1x1x1,cells=2x2x2", (dir / "box.mesh").string()});
  CHECK(converted.code == 0);
  CHECK(cli({"mesh", "info", (dir / "box.mesh").string(), "--json"}).out.find("\"tets\":48") != std::string::npos);
  CHECK(cli({"mesh", "convert", (dir / "box.mesh").string(), (dir / "box.vtu").string()}).code == 0);
  CHECK(fs::exists(dir / "box.vtu"));
  CHECK(cli({"mesh", "convert", (dir / "box.mesh").string(), (dir / "box.stl").string()}).code == 2);
  const Result missing = cli({"mesh", "info", (dir / "none.mesh").string()});
  CHECK(missing.code == 2);
  CHECK_THAT(missing.err, Catch::Matchers::Contains("none.mesh: cannot open file"));
  fs::remove_all(dir);
}

TEST_CASE("cli: list", "[cli]") {
  const Result scenes = cli({"list", "scenes"});
  CHECK(scenes.code == 0);
  CHECK_THAT(scenes.out, Catch::Matchers::Contains("plates20"));
  CHECK_THAT(scenes.out, Catch::Matchers::Contains("cube_drop"));
  const std::string methods = cli({"list", "methods"}).out;
  for (const char* m : {"full", "every_nth", "brute_force", "none"}) CHECK_THAT(methods, Catch::Matchers::Contains(m));
  CHECK(cli({"list", "widgets"}).code == 2);
}

TEST_CASE("cli: budgets and seeds are refused when out of range, never rewritten (issue 15, defect 1)", "[cli]") {
  const fs::path dir = fresh_dir("ranges");
  for (const std::vector<std::string>& bad : std::vector<std::vector<std::string>>{
           {"--budget-work", "18446744073709551615"}, {"--budget-work", "-5"}, {"--budget-work", "9223372036854775807"},
           {"--budget-work", "9007199254740993"}, {"--budget-work", "1.5"}, {"--budget-work", "2e4"},
           {"--budget-ms", "nan"}, {"--budget-ms", "inf"}, {"--budget-ms", "-1"}, {"--budget-ms", "1e-3"},
           {"--seed", "-1"}, {"--seed", "18446744073709551616"}, {"--seed", "abc"}, {"--seed", ""}}) {
    INFO(bad[0] << " " << bad[1]);
    fs::remove_all(dir / "bad");
    std::vector<std::string> args = {"run", "cube_drop", "--steps", "1", "--out", (dir / "bad").string()};
    args.insert(args.end(), bad.begin(), bad.end());
    const Result r = cli(args);
    CHECK(r.code == 2);
    CHECK_THAT(r.err, Catch::Matchers::Contains(bad[0]));
    CHECK_FALSE(fs::exists(dir / "bad"));
  }
  // The largest values are stored exactly as given.
  const Result big = cli({"run", "cube_drop", "--method", "interruptible", "--steps", "1", "--budget-work",
                          "9007199254740992", "--seed", "18446744073709551615", "--out", (dir / "big").string(),
                          "--quiet"});
  REQUIRE(big.code == 0);
  const auto run = nlohmann::json::parse(tcb::read_file(dir / "big" / "run.json"));
  CHECK(run["budget"]["value"].get<std::uint64_t>() == 9007199254740992ull);
  CHECK(run["budget"]["label"] == "work:9007199254740992");
  CHECK(run["seed"].get<std::uint64_t>() == 18446744073709551615ull);
  fs::remove_all(dir);
}

TEST_CASE("cli: check against a results directory that is not there is bad input (issue 15, defect 7)", "[cli]") {
  const fs::path missing = fresh_dir("no_results");
  const std::string thresholds = std::string(TCBENCH_DATA_DIR) + "/../experiments/thresholds/ci.toml";
  const Result r = cli({"check", thresholds, missing.string()});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Matchers::Contains("no such results directory"));
  const fs::path file = fresh_dir("a_file");
  tcb::write_file_atomically(file, "x");
  const Result f = cli({"check", thresholds, file.string()});
  CHECK(f.code == 2);
  CHECK_THAT(f.err, Catch::Matchers::Contains("is not a directory"));
  fs::remove(file);
}

TEST_CASE("cli: a scale that overflows the coordinates is bad input, naming the object (issue 15, defect 4)", "[cli]") {
  const fs::path dir = fresh_dir("overflow");
  const Result r = cli({"run", "cube_drop", "--set", "object.cube.scale=1e300", "--steps", "1", "--out", dir.string()});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Matchers::Contains("object 'cube': scale 1e+300 puts its coordinates beyond 1e+90 m"));
  CHECK_FALSE(fs::exists(dir));
}

TEST_CASE("cli: a cell size too small for the hash is bad input, not an unstable run (issue 15, defect 4)", "[cli]") {
  const fs::path dir = fresh_dir("tiny_cells");
  const Result r = cli({"run", "plates20", "--set", "collision.cell_size=1e-6", "--steps", "1", "--out", dir.string()});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Matchers::Contains("collision.cell_size = 1e-06 m: a tet of object"));
  CHECK_FALSE(fs::exists(dir));
}

TEST_CASE("cli: a directory given where a file belongs is named as such (issue 15, defect 4)", "[cli]") {
  const fs::path dir = fresh_dir("a_directory");
  fs::create_directories(dir);
  const fs::path with_ext = dir.string() + ".toml";  // resolved as a path, not a scene name
  fs::create_directories(with_ext);
  fs::create_directories(dir / "m.mesh");
  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
           {"run", with_ext.string(), "--steps", "1", "--out", (dir / "out").string()},
           {"sweep", with_ext.string(), "--out", (dir / "out").string()},
           {"check", with_ext.string(), dir.string()},
           {"mesh", "info", (dir / "m.mesh").string()}}) {
    INFO(args[0]);
    const Result r = cli(args);
    CHECK(r.code == 2);
    CHECK_THAT(r.err, Catch::Matchers::Contains("is a directory, not a file"));
  }
  fs::remove_all(dir);
  fs::remove_all(with_ext);
}

TEST_CASE("cli: messages say what was typed wrong and what is allowed (issue 15, defect 10)", "[cli]") {
  struct Case {
    std::vector<std::string> args;
    std::string message;
  };
  const std::vector<Case> cases = {
      {{"sweep", "x.toml", "--out", "o", "--jobs", "0"}, "--jobs: 0 is out of range; allowed: 1 .. 1024"},
      {{"sweep", "x.toml", "--out", "o", "--jobs", "2.5"}, "--jobs: '2.5' is not a whole number; allowed: 1 .. 1024"},
      {{"run", "cube_drop", "--steps", "abc"}, "--steps: 'abc' is not a whole number; allowed: 0 .. 1099511627776"},
      {{"run", "cube_drop", "--steps", "1e20"}, "--steps: '1e20' is not a whole number"},
      {{"run", "cube_drop", "--steps", "-5"}, "--steps: -5 is out of range"},
      {{"run", "cube_drop", "--steps", "99999999999999999999999"}, "is out of range; allowed: 0 .. 1099511627776"},
      {{"run", "cube_drop", "--record", "0"}, "--record: 0 is out of range; allowed: 1 .."},
      {{"neural", "gen", "--out", "c.csv", "--codes", "1e3"}, "--codes: '1e3' is not a whole number; allowed: 1 .."},
      {{"neural", "alm", "--model", "m.json", "--path", "p.csv", "--out", "a.csv", "--margin", "nan"},
       "--margin: 'nan' is not a finite number; allowed: -100 .. 100"},
      {{"neural", "alm", "--model", "m.json", "--path", "p.csv", "--out", "a.csv", "--margin", "101"},
       "--margin: 101 is out of range; allowed: -100 .. 100"},
      {{"run", "cube_drop", "--out", ""}, "--out: is empty; name a file or directory"},
      {{"sweep", "x.toml", "--out", ""}, "--out: is empty"},
      {{"neural", "gen", "--out", ""}, "--out: is empty"},
      {{"frobnicate"}, "unknown command 'frobnicate' (commands: run, sweep, check, compare,"},
      {{}, "no command given (commands: run,"},
  };
  for (const Case& c : cases) {
    std::string line;
    for (const auto& a : c.args) line += a + " ";
    INFO(line);
    const Result r = cli(c.args);
    CHECK(r.code == 2);
    CHECK_THAT(r.err + r.out, Catch::Matchers::Contains(c.message));
    CHECK(r.err.find("not in range") == std::string::npos);  // CLI11's own, with DBL_MAX in 309 digits
    // One line, as every bad input is said.
    CHECK(r.err.rfind("tcbench: error: ", 0) == 0);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  }
  // A usage error points to the help of the command it was typed for.
  CHECK_THAT(cli({"view", "some_dir", "--port", "abc"}).err,
             Catch::Matchers::StartsWith("tcbench: error: ") && Catch::Matchers::EndsWith("(tcbench view --help)\n"));
  CHECK_THAT(cli({"mesh", "info", "--bogus"}).err, Catch::Matchers::EndsWith("(tcbench mesh info --help)\n"));
  CHECK_THAT(cli({"--bogus"}).err, Catch::Matchers::EndsWith("(tcbench --help)\n"));
}

TEST_CASE("cli: a whole number is stored as it was checked, never read as octal", "[cli]") {
  // CLI11 converts "010" with base 0, as octal 8; the check passed it as 10.
  const fs::path dir = fresh_dir("octal");
  REQUIRE(cli({"run", "cube_drop", "--steps", "010", "--seed", "010", "--out", dir.string(), "--quiet"}).code == 0);
  const auto run = nlohmann::json::parse(tcb::read_file(dir / "run.json"));
  CHECK(run["steps"] == 10);
  CHECK(cli({"run", "cube_drop", "--steps", "08", "--out", (dir / "b").string(), "--quiet"}).code == 0);
  CHECK(nlohmann::json::parse(tcb::read_file(dir / "b" / "run.json"))["steps"] == 8);
  fs::remove_all(dir);
}
