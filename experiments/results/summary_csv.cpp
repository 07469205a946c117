#include "experiments/results/summary_csv.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <map>

#include "sim/io/atomic_file.hpp"

namespace tcb {
namespace {

using Json = nlohmann::json;

void flatten(const Json& node, const std::string& prefix, std::vector<std::pair<std::string, std::string>>& out) {
  if (node.is_object()) {
    for (auto it = node.begin(); it != node.end(); ++it)
      flatten(it.value(), prefix.empty() ? it.key() : prefix + "." + it.key(), out);
  } else if (node.is_number()) {
    out.emplace_back(prefix, node.dump());
  } else if (node.is_string()) {
    out.emplace_back(prefix, node.get<std::string>());  // timing.verdict: a sweep records it per run
  } else if (node.is_null()) {
    out.emplace_back(prefix, "");
  }  // arrays (oracle_unmeasured, timing.reasons, ...) stay in run.json
}

}  // namespace

std::string csv_cell(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (const char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

namespace {

// steps.csv holds a header and `steps` rows of the header's width.
bool steps_csv_agrees(const std::filesystem::path& file, std::int64_t steps) {
  std::ifstream in(file);
  std::string line;
  if (!in || !std::getline(in, line) || line.rfind("step,", 0) != 0) return false;
  const auto width = std::count(line.begin(), line.end(), ',');
  std::int64_t rows = 0;
  while (std::getline(in, line)) {
    if (std::count(line.begin(), line.end(), ',') != width) return false;
    ++rows;
  }
  return rows == steps;
}

}  // namespace

std::optional<Json> read_complete_run(const std::filesystem::path& run_dir) {
  std::ifstream in(run_dir / "run.json");
  if (!in) return std::nullopt;
  try {
    Json j = Json::parse(in);
    if (j.contains("summary") && j.contains("status") && j.contains("steps") && j["steps"].is_number_integer() &&
        steps_csv_agrees(run_dir / "steps.csv", j["steps"].get<std::int64_t>()))
      return j;
  } catch (const Json::exception&) {
  }
  return std::nullopt;
}

SummaryLookup find_summary_metric(const Json& run, const std::string& dotted) {
  const Json* node = &run.at("summary");
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = dotted.find('.', start);
    const std::string key = dotted.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    if (!node->is_object() || !node->contains(key)) return {false, std::nullopt};
    node = &(*node)[key];
    if (dot == std::string::npos) break;
    if (node->is_null()) return {true, std::nullopt};  // a null group: its members were not measured
    start = dot + 1;
  }
  return {true, node->is_number() ? std::optional<double>(node->get<double>()) : std::nullopt};
}

std::optional<double> summary_metric(const Json& run, const std::string& dotted) {
  return find_summary_metric(run, dotted).value;
}

void write_summary_csv(const std::filesystem::path& path, const std::vector<SummaryRow>& rows) {
  const std::vector<std::string> fixed = {"run",          "scene",          "method",       "method_label",
                                          "budget",       "budget_kind",    "budget_value", "seed",
                                          "threads",      "handover_start", "handover_end", "mesh_order",
                                          "overrides",    "status",         "steps",        "wall_s"};
  std::vector<std::string> metrics;  // in order of first appearance
  std::map<std::string, bool> known;
  std::vector<std::map<std::string, std::string>> cells(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    auto& c = cells[i];
    c["run"] = rows[i].run;
    c["status"] = rows[i].status;
    if (!rows[i].record) continue;
    const Json& r = *rows[i].record;
    // Absent fields (a hand-written or older run.json) give empty cells.
    const auto field = [&](const Json& j, const char* key) { return j.is_object() ? j.value(key, Json()) : Json(); };
    const auto text = [](const Json& j) { return j.is_null() ? std::string() : j.is_string() ? j.get<std::string>() : j.dump(); };
    const Json budget = field(r, "budget");
    c["scene"] = text(field(r, "scene"));
    c["method"] = text(field(r, "method"));
    c["method_label"] = r.contains("method_label") ? text(field(r, "method_label")) : c["method"];
    c["budget"] = text(field(budget, "label"));
    c["budget_kind"] = text(field(budget, "kind"));
    c["budget_value"] = text(field(budget, "value"));
    c["seed"] = text(field(r, "seed"));
    c["threads"] = text(field(field(r, "collision"), "threads"));  // collision.threads: wall times depend on it
    // and on how cheaply the cores hand each other lines (empty where not probed)
    const Json handover = field(field(r, "collision"), "handover_ratio");
    c["handover_start"] = text(field(handover, "start"));
    c["handover_end"] = text(field(handover, "end"));
    // world.mesh_order: renumbered vertices change sums, and under a budget the order of work
    c["mesh_order"] = text(field(field(r, "world"), "mesh_order"));
    std::string overrides;
    const Json scene_overrides = field(r, "overrides");
    if (scene_overrides.is_array())
      for (const auto& o : scene_overrides) {
        if (!overrides.empty()) overrides += ';';
        overrides += text(o);
      }
    c["overrides"] = overrides;
    c["status"] = text(field(r, "status"));
    c["steps"] = text(field(r, "steps"));
    c["wall_s"] = text(field(r, "wall_s"));
    std::vector<std::pair<std::string, std::string>> flat;
    if (const Json summary = field(r, "summary"); summary.is_object()) flatten(summary, "", flat);
    for (const auto& [key, value] : flat) {
      if (!known[key]) metrics.push_back(key), known[key] = true;
      c[key] = value;
    }
  }
  AtomicFile file(path);
  std::string line;
  for (const auto& name : fixed) {
    if (!line.empty()) line += ',';
    line += name;
  }
  for (const auto& name : metrics) {
    line += ',';
    line += name;
  }
  file.stream() << line << '\n';
  for (const auto& c : cells) {
    line.clear();
    bool first = true;
    for (const std::vector<std::string>* names : {&fixed, static_cast<const std::vector<std::string>*>(&metrics)})
      for (const auto& name : *names) {
        const auto it = c.find(name);
        if (!first) line += ',';
        line += csv_cell(it == c.end() ? std::string() : it->second);
        first = false;
      }
    file.stream() << line << '\n';
  }
  file.commit();
}

}  // namespace tcb
