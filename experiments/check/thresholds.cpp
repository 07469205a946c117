#include "experiments/check/thresholds.hpp"

#include "experiments/sweep/sweep_plan.hpp"

#include "experiments/results/summary_csv.hpp"
#include "experiments/scene/toml_table_reader.hpp"

namespace tcb {

std::vector<Threshold> load_thresholds(const std::filesystem::path& path) {
  const toml::table root = parse_toml_file(path);
  const Origins origins{path.string(), {}};
  TableReader top(root, "thresholds file", origins);
  const toml::node* list = top.node("threshold");
  top.finish();
  const toml::array* array = list ? list->as_array() : nullptr;
  if (!array || array->empty()) throw InputError(path.string(), 1, "expected one or more [[threshold]] tables");
  std::vector<Threshold> out;
  for (const auto& node : *array) {
    const toml::table* t = node.as_table();
    if (!t) throw InputError(path.string(), static_cast<int>(node.source().begin.line), "threshold must be a table");
    TableReader r(*t, "threshold", origins);
    Threshold th;
    th.line = static_cast<int>(t->source().begin.line);
    const auto need = [&](std::string_view key) {
      const auto v = r.string(key);
      if (!v || v->empty()) throw InputError(path.string(), th.line, "threshold: '" + std::string(key) + "' is required");
      return *v;
    };
    th.scene = need("scene");
    th.method = need("method");
    th.metric = need("metric");
    th.budget = r.string("budget").value_or("none");
    // The label as run.json records it: absolute budgets in their one
    // spelling, relative ones (full/3) as written; anything else is a typo.
    if (const auto b = parse_sweep_budget(th.budget)) th.budget = b->label;
    else r.fail("budget", "'" + th.budget + "' is not none, ms:X, work:N, full/K or full-work/K");
    if (const auto seed = r.integer("seed", 0, std::int64_t{1} << 62)) th.seed = static_cast<std::uint64_t>(*seed);
    th.min = r.number("min");
    th.max = r.number("max");
    if (!th.min && !th.max) throw InputError(path.string(), th.line, "threshold: give min, max or both");
    if (th.min && th.max && *th.min > *th.max) r.fail("min", "is above max");
    r.finish();
    out.push_back(th);
  }
  return out;
}

std::vector<CheckRow> check_thresholds(const std::vector<Threshold>& thresholds, const std::filesystem::path& dir) {
  // Run directories: DIR and every folder beneath it holding a complete
  // run.json (a sweep's DIR/runs/*, reproduce's DIR/<sweep>/runs/*), named by
  // their path relative to DIR. Reports and frames are not searched.
  std::vector<std::pair<std::string, nlohmann::json>> runs;
  const auto consider = [&](const std::filesystem::path& d) {
    if (auto r = read_complete_run(d)) {
      const std::string name = d == dir ? d.filename().string() : std::filesystem::relative(d, dir).string();
      runs.emplace_back(name, std::move(*r));
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
  std::sort(runs.begin(), runs.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<CheckRow> rows;
  for (const Threshold& th : thresholds) {
    bool matched = false;
    for (const auto& [name, run] : runs) {
      if (run.value("scene", "") != th.scene || run.value("method_label", run.value("method", "")) != th.method)
        continue;
      const nlohmann::json budget = run.value("budget", nlohmann::json::object());
      if (budget.value("label", "none") != th.budget) continue;
      if (th.seed && run.value("seed", std::uint64_t{0}) != *th.seed) continue;
      matched = true;
      CheckRow row{&th, name, summary_metric(run, th.metric), ""};
      const bool ok = row.value && (!th.min || *row.value >= *th.min) && (!th.max || *row.value <= *th.max);
      row.verdict = !row.value ? "missing" : ok ? "pass" : "FAIL";
      rows.push_back(row);
    }
    if (!matched) rows.push_back({&th, "", std::nullopt, "missing"});
  }
  return rows;
}

}  // namespace tcb
