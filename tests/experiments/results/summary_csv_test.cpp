// A run counts as complete (and `sweep --resume` skips it) only when run.json
// and steps.csv are both whole and agree (issue 15, defect 8).
#include "experiments/results/summary_csv.hpp"

#include <catch2/catch.hpp>

#include <unistd.h>

#include "experiments/run/run_scene.hpp"
#include "experiments/scene/scene_file.hpp"
#include "sim/io/atomic_file.hpp"

using namespace tcb;
namespace fs = std::filesystem;

TEST_CASE("a run is complete only when run.json and steps.csv agree", "[results]") {
  const fs::path dir = fs::temp_directory_path() / ("tcbench_complete_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  RunOptions options;
  options.steps = 5;
  options.out_dir = dir;
  REQUIRE(run_scene(load_scene_file(resolve_scene("cube_drop", default_scene_dirs())), options).status == "ok");
  REQUIRE(read_complete_run(dir).has_value());
  const std::string csv = read_file(dir / "steps.csv");
  const std::string header = csv.substr(0, csv.find('\n') + 1);
  const auto restore = [&] { write_file_atomically(dir / "steps.csv", csv); };

  write_file_atomically(dir / "steps.csv", "garbage\n");
  CHECK_FALSE(read_complete_run(dir).has_value());
  write_file_atomically(dir / "steps.csv", header);  // rows missing
  CHECK_FALSE(read_complete_run(dir).has_value());
  write_file_atomically(dir / "steps.csv", csv + csv.substr(header.size(), csv.find('\n', header.size()) + 1 - header.size()));
  CHECK_FALSE(read_complete_run(dir).has_value());  // one row too many
  std::string short_row = csv;
  short_row.erase(short_row.rfind(','), short_row.size() - short_row.rfind(',') - 1);  // last row loses a cell
  write_file_atomically(dir / "steps.csv", short_row);
  CHECK_FALSE(read_complete_run(dir).has_value());
  fs::remove(dir / "steps.csv");
  CHECK_FALSE(read_complete_run(dir).has_value());
  restore();
  CHECK(read_complete_run(dir).has_value());
  write_file_atomically(dir / "run.json", "{\"summary\": {}");  // truncated
  CHECK_FALSE(read_complete_run(dir).has_value());
  fs::remove_all(dir);
}

TEST_CASE("summary.csv says who ran: fixed columns, threads, handover and mesh order among them, "
          "then the summary's keys",
          "[results]") {
  const fs::path dir = fs::temp_directory_path() / ("tcbench_summary_csv_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const nlohmann::json threaded = nlohmann::json::parse(R"({"scene": "plates20", "method": "full", "seed": 3,
      "budget": {"kind": "none", "value": 0, "label": "none"},
      "collision": {"threads": 2, "handover_ratio": {"start": 1.25, "end": 2.5}},
      "world": {"mesh_order": "curve"},
      "status": "ok", "steps": 4, "wall_s": 0.5, "summary": {"handling_ms": {"p99": 1.5}, "verdict": "a,b"}})");
  nlohmann::json older = threaded;
  older.erase("collision");  // a run.json from before threads, handover and the mesh order were recorded
  older.erase("world");
  // As a run writes them: one thread, no probe; two, pinned (no ratio at either end).
  nlohmann::json single = threaded, pinned = threaded;
  single["collision"] = {{"threads", 1}, {"handover_ratio", nullptr}};
  pinned["collision"]["handover_ratio"] = {{"start", nullptr}, {"end", nullptr}};
  write_summary_csv(dir / "summary.csv", {{"r1", threaded, ""},
                                          {"r2", older, ""},
                                          {"r3", std::nullopt, "failed"},
                                          {"r4", single, ""},
                                          {"r5", pinned, ""}});
  std::istringstream in(read_file(dir / "summary.csv"));
  std::string header, first, second, third, fourth, fifth;
  std::getline(in, header);
  std::getline(in, first);
  std::getline(in, second);
  std::getline(in, third);
  std::getline(in, fourth);
  std::getline(in, fifth);
  CHECK(header ==
        "run,scene,method,method_label,budget,budget_kind,budget_value,seed,threads,handover_start,handover_end,"
        "mesh_order,overrides,status,steps,wall_s,handling_ms.p99,verdict");
  CHECK(first == "r1,plates20,full,full,none,none,0,3,2,1.25,2.5,curve,,ok,4,0.5,1.5,\"a,b\"");
  CHECK(second == "r2,plates20,full,full,none,none,0,3,,,,,,ok,4,0.5,1.5,\"a,b\"");
  CHECK(third == "r3,,,,,,,,,,,,,failed,,,,");
  CHECK(fourth == "r4,plates20,full,full,none,none,0,3,1,,,curve,,ok,4,0.5,1.5,\"a,b\"");
  CHECK(fifth == "r5,plates20,full,full,none,none,0,3,2,,,curve,,ok,4,0.5,1.5,\"a,b\"");
  fs::remove_all(dir);
}
