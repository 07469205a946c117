#include "experiments/results/run_collection.hpp"

#include <algorithm>
#include <map>

#include "experiments/results/summary_csv.hpp"

namespace tcb {
namespace {

nlohmann::json configuration_of(const nlohmann::json& run) {
  return {{"scene", run.value("scene", "")},
          {"method", run.value("method_label", run.value("method", ""))},
          {"settings", run.value("settings", nlohmann::json::object())},
          {"budget", run.value("budget", nlohmann::json::object()).value("label", "none")},
          {"response", run.value("response", "explicit")},
          // Renumbered vertices (world.mesh_order "curve") change the order of
          // sums and, under a budget, of the cycle's work: not repeats of the
          // file's numbering.
          {"mesh_order", mesh_order_of(run)},
          {"steps", run.value("steps_requested", run.value("steps", std::int64_t{0}))},
          {"overrides", run.value("overrides", nlohmann::json::array())}};
}

}  // namespace

std::string mesh_order_of(const nlohmann::json& record) {
  const nlohmann::json world = record.value("world", nlohmann::json::object());
  return world.is_object() ? world.value("mesh_order", "file") : "file";
}

std::vector<CollectedRun> collect_runs(const std::filesystem::path& dir) {
  std::vector<CollectedRun> runs;
  const auto consider = [&](const std::filesystem::path& d) {
    if (auto r = read_complete_run(d)) {
      const std::string name = d == dir ? d.filename().string() : std::filesystem::relative(d, dir).string();
      runs.push_back({name, d, std::move(*r)});
    }
  };
  consider(dir);
  if (std::filesystem::is_directory(dir))
    for (auto it = std::filesystem::recursive_directory_iterator(dir); it != decltype(it){}; ++it) {
      if (!it->is_directory()) continue;
      const std::string leaf = it->path().filename().string();
      if (leaf == "report" || leaf == "frames") {
        it.disable_recursion_pending();
        continue;
      }
      consider(it->path());
    }
  std::sort(runs.begin(), runs.end(), [](const CollectedRun& a, const CollectedRun& b) { return a.name < b.name; });
  return runs;
}

std::string configuration_key(const nlohmann::json& record) { return configuration_of(record).dump(); }

std::string configuration_label(const nlohmann::json& record) {
  const nlohmann::json c = configuration_of(record);
  std::string label = c["scene"].get<std::string>() + " " + c["method"].get<std::string>() + " " +
                      c["budget"].get<std::string>() + " " + c["response"].get<std::string>() + " " +
                      std::to_string(c["steps"].get<std::int64_t>()) + " steps";
  if (c["mesh_order"] != "file") label += " mesh_order=" + c["mesh_order"].get<std::string>();
  if (!c["overrides"].empty()) {
    std::string sets;
    for (const auto& o : c["overrides"]) {
      if (!sets.empty()) sets += ' ';
      sets += o.get<std::string>();
    }
    label += " [" + sets + "]";
  }
  return label;
}

const std::vector<std::string>& headline_metrics() {
  static const std::vector<std::string> metrics = {
      "handling_ms.p50",  "handling_ms.p99",   "step_ms.p50",  "overshoot_pct.p99",
      "work_units_total", "recall_mean",       "recall_min",   "precision_min",
      "depth_err.mean",   "latency_steps.max", "tunneling",    "jitter",
      "top_centre_height_m.final", "force_error.relative_l2.p50", "divergence.rms_m.final"};
  return metrics;
}

std::vector<std::vector<const CollectedRun*>> group_repeats(const std::vector<CollectedRun>& runs) {
  std::vector<std::vector<const CollectedRun*>> groups;
  std::map<std::string, std::size_t> index;
  for (const CollectedRun& r : runs) {
    const auto [it, fresh] = index.emplace(configuration_key(r.record), groups.size());
    if (fresh) groups.emplace_back();
    groups[it->second].push_back(&r);
  }
  for (auto& g : groups)
    std::stable_sort(g.begin(), g.end(), [](const CollectedRun* a, const CollectedRun* b) {
      return a->record.value("seed", std::uint64_t{0}) < b->record.value("seed", std::uint64_t{0});
    });
  return groups;
}

}  // namespace tcb
