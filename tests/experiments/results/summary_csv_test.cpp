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
