#include "experiments/cli/screenshot_runner.hpp"

#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "experiments/cli/report_runner.hpp"
#include "experiments/run/provenance.hpp"
#include "sim/io/atomic_file.hpp"

namespace tcb::cli {
namespace {

using Json = nlohmann::json;

}  // namespace

Json viewer_screenshot_runs(const std::filesystem::path& sweep_dir) {
  std::filesystem::path full, interruptible;
  const std::filesystem::path runs = sweep_dir / "runs";
  if (!std::filesystem::is_directory(runs)) return Json::array();
  for (const auto& entry : std::filesystem::directory_iterator(runs)) {
    std::ifstream in(entry.path() / "run.json");
    const Json run = Json::parse(in, nullptr, false);
    if (run.is_discarded() || !run.is_object() || run.value("scene", "") != "plates20" || run["replay"].is_null() ||
        run.value("response", "") != "implicit" || run.value("seed", 1) != 0 || run.value("status", "") != "ok")
      continue;
    // The label: "full" only with every setting at its default (not keep_table).
    const std::string method = run.value("method_label", run.value("method", ""));
    const std::string budget = run["budget"].value("label", "");
    if (method == "full" && budget == "none") full = entry.path();
    if (method == "interruptible" && budget == "full-work/3") interruptible = entry.path();
  }
  if (full.empty() || interruptible.empty()) return Json::array();
  return Json::array({full.string(), interruptible.string()});
}

Json make_viewer_screenshot(const std::filesystem::path& results_dir, const std::filesystem::path& tcbench) {
  const std::filesystem::path out_dir = results_dir / "viewer";
  std::filesystem::create_directories(out_dir);
  const std::string png = "plates20_full_interruptible.png";
  Json record = {{"screenshot", nullptr}, {"runs", viewer_screenshot_runs(results_dir / "1_stack")}};
  const auto finish = [&](const std::string& status, const std::string& reason) {
    record["status"] = status;
    record["reason"] = reason;
    write_file_atomically(out_dir / "viewer.json", record.dump(1) + "\n");
    if (status != "ok") std::cerr << "reproduce: no viewer screenshot: " << reason << '\n';
    return record;
  };
  if (record["runs"].empty())
    return finish("skipped", "the stack sweep holds no recorded plates20 runs of full and interruptible @ full-work/3");
  std::int64_t step = 0;
  {
    std::ifstream in(std::filesystem::path(record["runs"][0].get<std::string>()) / "run.json");
    step = Json::parse(in).value("steps", std::int64_t{0});
  }
  record["step"] = step;
  const std::filesystem::path script = source_tree_dir() / "viewer" / "screenshot.mjs";
  std::filesystem::remove(out_dir / png);
  std::vector<std::string> args = {"node", script.string(), tcbench.string(), (out_dir / png).string(),
                                   std::to_string(step)};
  for (const auto& run : record["runs"]) args.push_back(run.get<std::string>());
  const int status = run_program(args);
  if (status == 0 && std::filesystem::is_regular_file(out_dir / png)) {
    record["screenshot"] = png;
    return finish("ok", "");
  }
  return finish(status == 77 ? "skipped" : "failed",
                status == 127 || status < 0 ? "node could not be started (scripts/setup installs it)"
                : status == 77 ? "no browser could start here (scripts/setup installs chromium)"
                               : "viewer/screenshot.mjs exited " + std::to_string(status) + " (its message is above)");
}

}  // namespace tcb::cli
