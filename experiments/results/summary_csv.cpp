#include "experiments/results/summary_csv.hpp"

#include <fmt/format.h>

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
  } else if (node.is_null()) {
    out.emplace_back(prefix, "");
  }  // arrays and strings (oracle_unmeasured, ...) stay in run.json
}

std::string csv_cell(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (const char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

}  // namespace

std::optional<Json> read_complete_run(const std::filesystem::path& run_dir) {
  std::ifstream in(run_dir / "run.json");
  if (!in) return std::nullopt;
  try {
    Json j = Json::parse(in);
    if (j.contains("summary") && j.contains("status")) return j;
  } catch (const Json::exception&) {
  }
  return std::nullopt;
}

std::optional<double> summary_metric(const Json& run, const std::string& dotted) {
  const Json* node = &run.at("summary");
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = dotted.find('.', start);
    const std::string key = dotted.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    if (!node->is_object() || !node->contains(key)) return std::nullopt;
    node = &(*node)[key];
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  if (!node->is_number()) return std::nullopt;
  return node->get<double>();
}

void write_summary_csv(const std::filesystem::path& path, const std::vector<SummaryRow>& rows) {
  const std::vector<std::string> fixed = {"run",  "scene",        "method",    "method_label", "budget", "budget_kind",
                                          "budget_value", "seed", "overrides", "status",       "steps",  "wall_s"};
  std::vector<std::string> metrics;  // in order of first appearance
  std::map<std::string, bool> known;
  std::vector<std::map<std::string, std::string>> cells(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    auto& c = cells[i];
    c["run"] = rows[i].run;
    c["status"] = rows[i].status;
    if (!rows[i].record) continue;
    const Json& r = *rows[i].record;
    c["scene"] = r.value("scene", "");
    c["method"] = r.value("method", "");
    c["method_label"] = r.value("method_label", c["method"]);
    c["budget"] = r["budget"].value("label", "");
    c["budget_kind"] = r["budget"].value("kind", "");
    c["budget_value"] = r["budget"]["value"].is_null() ? "" : r["budget"]["value"].dump();
    c["seed"] = r["seed"].dump();
    std::string overrides;
    for (const auto& o : r["overrides"]) {
      if (!overrides.empty()) overrides += ';';
      overrides += o.get<std::string>();
    }
    c["overrides"] = overrides;
    c["status"] = r.value("status", "");
    c["steps"] = r["steps"].dump();
    c["wall_s"] = r["wall_s"].dump();
    std::vector<std::pair<std::string, std::string>> flat;
    flatten(r["summary"], "", flat);
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
