// The viewer's screenshot for the report: which runs of the stack sweep it
// shows, and (where chromium is installed, as scripts/setup does) that
// viewer/screenshot.mjs writes it and viewer.json says so; elsewhere that
// viewer.json says why there is none.
#include "experiments/cli/screenshot_runner.hpp"

#include <catch2/catch.hpp>

#include <unistd.h>

#include <fstream>
#include <functional>

#include "experiments/run/provenance.hpp"
#include "sim/io/atomic_file.hpp"

using namespace tcb;
namespace fs = std::filesystem;
using Json = nlohmann::json;

namespace {

// A copy of a committed recording of two_blocks, its run.json saying what the
// stack sweep's run would say (the picture does not depend on the scene).
void stack_run(const fs::path& runs, const std::string& name, const std::string& from,
               const std::function<void(Json&)>& edit) {
  const fs::path dir = runs / name;
  fs::create_directories(dir);
  const fs::path source = source_tree_dir() / "tests" / "data" / "viewer" / from;
  for (const char* f : {"replay.bin", "replay.json", "steps.csv"}) fs::copy_file(source / f, dir / f);
  Json run = Json::parse(read_file(source / "run.json"));
  run["scene"] = "plates20";
  edit(run);
  write_file_atomically(dir / "run.json", run.dump());
}

}  // namespace

TEST_CASE("viewer screenshot: full and interruptible @ full-work/3 of the stack, implicit, seed 0", "[viewer]") {
  const fs::path root = fs::temp_directory_path() / ("tcbench_screenshot_" + std::to_string(::getpid()));
  fs::remove_all(root);
  const fs::path runs = root / "1_stack" / "runs";
  CHECK(cli::viewer_screenshot_runs(root / "1_stack").empty());
  stack_run(runs, "a-full", "two_blocks-full", [](Json&) {});
  stack_run(runs, "b-explicit", "two_blocks-interruptible", [](Json& r) {
    r["budget"]["label"] = "full-work/3";
    r["response"] = "explicit";
  });
  stack_run(runs, "c-seed1", "two_blocks-interruptible", [](Json& r) {
    r["budget"]["label"] = "full-work/3";
    r["seed"] = 1;
  });
  CHECK(cli::viewer_screenshot_runs(root / "1_stack").empty());  // no implicit seed-0 interruptible yet
  const Json none = cli::make_viewer_screenshot(root, TCBENCH_EXE);
  CHECK(none["status"] == "skipped");
  CHECK(Json::parse(read_file(root / "viewer" / "viewer.json"))["reason"] == none["reason"]);

  stack_run(runs, "d-interruptible", "two_blocks-interruptible", [](Json& r) { r["budget"]["label"] = "full-work/3"; });
  const Json chosen = cli::viewer_screenshot_runs(root / "1_stack");
  REQUIRE(chosen.size() == 2);
  CHECK(chosen[0] == (runs / "a-full").string());
  CHECK(chosen[1] == (runs / "d-interruptible").string());

  const Json record = cli::make_viewer_screenshot(root, TCBENCH_EXE);
  CHECK(Json::parse(read_file(root / "viewer" / "viewer.json")) == record);
  if (fs::exists("/usr/bin/chromium")) {
    INFO(record.dump());
    CHECK(record["status"] == "ok");
    CHECK(record["step"] == 150);
    CHECK(fs::file_size(root / "viewer" / "plates20_full_interruptible.png") > 10000);
  } else {
    CHECK(record["status"] == "skipped");
    CHECK_FALSE(record["reason"].get<std::string>().empty());
  }
  fs::remove_all(root);
}
