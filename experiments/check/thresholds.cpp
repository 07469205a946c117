#include "experiments/check/thresholds.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

#include "experiments/sweep/sweep_plan.hpp"

#include "experiments/results/run_collection.hpp"
#include "experiments/results/summary_csv.hpp"
#include "experiments/scene/toml_table_reader.hpp"

namespace tcb {

// The thresholds of a parsed file (below).
static std::vector<Threshold> thresholds_of(const toml::table& root, const std::filesystem::path& path);

std::vector<Threshold> load_thresholds(const std::filesystem::path& path) {
  return thresholds_of(parse_toml_file(path), path);
}

std::vector<Threshold> parse_thresholds(std::string_view text, const std::filesystem::path& path) {
  return thresholds_of(parse_toml_text(text, path), path);
}

static std::vector<Threshold> thresholds_of(const toml::table& root, const std::filesystem::path& path) {
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
    th.status = r.string("status");
    if (th.status && *th.status != "ok" && *th.status != "unstable") r.fail("status", "is \"ok\" or \"unstable\"");
    th.reason = r.string("reason");
    if (th.reason && th.status != "unstable") r.fail("reason", "needs status = \"unstable\"");
    th.set = r.string_list("set");
    if (th.set) std::sort(th.set->begin(), th.set->end());
    th.metric = th.status ? r.string("metric").value_or("") : need("metric");
    const auto is = [&](const std::string& key) { return th.metric == key || th.metric.rfind(key + ".", 0) == 0; };
    th.wall_metric = is("handling_ms") || is("overshoot_pct") || is("dynamics_ms");
    const bool cpu_metric = is("handling_cpu_ms") || is("overshoot_cpu_pct");  // the thread's own time: never
    th.budget = r.string("budget").value_or("none");
    // The label as run.json records it: absolute budgets in their one
    // spelling, relative ones (full/3) as written; anything else is a typo.
    if (const auto b = parse_sweep_budget(th.budget)) {
      th.budget = b->label;
      // ms:0 is spent at the first poll on any machine: it decides nothing by the clock.
      th.wall_budget = !cpu_metric && (b->relative == SweepBudget::Relative::FullMs ||
                                       (!b->is_relative() && b->absolute.kind == BudgetKind::WallMs &&
                                        b->absolute.value > 0.0));
    } else {
      r.fail("budget", "'" + th.budget + "' is not none, ms:X, work:N, full/K or full-work/K");
    }
    if (const auto seed = r.integer("seed", 0, std::int64_t{1} << 62)) th.seed = static_cast<std::uint64_t>(*seed);
    th.response = r.string("response");
    if (th.response && *th.response != "implicit" && *th.response != "explicit")
      r.fail("response", "is \"implicit\" or \"explicit\"");
    th.relative_to = r.string("relative_to");
    if (th.relative_to && th.relative_to->empty()) r.fail("relative_to", "names a method label, e.g. \"full\"");
    th.min = r.number("min");
    th.max = r.number("max");
    if (th.metric.empty() && (th.min || th.max || th.relative_to))
      throw InputError(path.string(), th.line, "threshold: min, max and relative_to bound a 'metric', which is missing");
    if (!th.metric.empty() && !th.min && !th.max)
      throw InputError(path.string(), th.line, "threshold: give min, max or both");
    if (th.min && th.max && *th.min > *th.max) r.fail("min", "is above max");
    r.finish();
    out.push_back(th);
  }
  return out;
}

namespace {

/// What a threshold matches a run by, read once per run.
struct RunKey {
  std::string name;  ///< path below DIR
  std::filesystem::path folder;
  std::string scene, method_label, budget, response, mesh_order, status, reason;
  std::uint64_t seed = 0;
  std::int64_t steps = 0;
  nlohmann::json overrides;
  bool noisy = false;
  const nlohmann::json* record = nullptr;
};

RunKey key_of(std::string name, const nlohmann::json& run) {
  RunKey k;
  k.folder = std::filesystem::path(name).parent_path();
  k.name = std::move(name);
  k.scene = run.value("scene", "");
  k.method_label = run.value("method_label", run.value("method", ""));  // tcbench.run/1 had no label
  k.budget = run.value("budget", nlohmann::json::object()).value("label", "none");
  k.response = run.value("response", "explicit");  // runs recorded before the field were explicit
  k.mesh_order = mesh_order_of(run);
  k.seed = run.value("seed", std::uint64_t{0});
  k.steps = run.value("steps_requested", run.value("steps", std::int64_t{0}));
  k.overrides = run.value("overrides", nlohmann::json::array());
  k.status = run.value("status", "");
  const nlohmann::json reason = run.value("unstable_reason", nlohmann::json());
  k.reason = reason.is_string() ? reason.get<std::string>() : "";
  const nlohmann::json summary = run.value("summary", nlohmann::json::object());
  k.noisy = summary.is_object() && summary.value("timing", nlohmann::json::object()).value("verdict", "") == "noisy";
  k.record = &run;
  return k;
}

/// A run's --set overrides, sorted: a threshold's `set` matches them in any order.
std::vector<std::string> sorted_strings(const nlohmann::json& list) {
  std::vector<std::string> out;
  for (const auto& e : list)
    if (e.is_string()) out.push_back(e.get<std::string>());
  std::sort(out.begin(), out.end());
  return out;
}

/// The run a relative threshold divides by; null when there is none.
const RunKey* reference_of(const RunKey& run, const std::string& label, const std::vector<RunKey>& runs) {
  for (const RunKey& o : runs)
    if (o.folder == run.folder && o.scene == run.scene && o.method_label == label && o.budget == "none" &&
        o.seed == run.seed && o.response == run.response && o.mesh_order == run.mesh_order && o.steps == run.steps &&
        o.overrides == run.overrides)
      return &o;
  return nullptr;
}

}  // namespace

std::vector<CheckRow> check_thresholds(const std::vector<Threshold>& thresholds, const std::filesystem::path& dir) {
  const std::vector<CollectedRun> records = collect_runs(dir);
  std::vector<RunKey> runs;
  for (const CollectedRun& r : records) runs.push_back(key_of(r.name, r.record));
  std::vector<CheckRow> rows;
  for (const Threshold& th : thresholds) {
    bool matched = false;
    for (const RunKey& run : runs) {
      if (run.scene != th.scene || run.method_label != th.method || run.budget != th.budget) continue;
      if ((th.seed && run.seed != *th.seed) || (th.response && run.response != *th.response)) continue;
      if (th.set && sorted_strings(run.overrides) != *th.set) continue;
      matched = true;
      CheckRow row;
      row.threshold = &th;
      row.run = run.name;
      row.status = run.status;
      if (th.status) {
        const bool as_expected = run.status == *th.status && (!th.reason || run.reason.find(*th.reason) != std::string::npos);
        if (!as_expected || th.metric.empty()) {
          row.status_check = true;
          row.verdict = as_expected ? "pass" : "FAIL";
          rows.push_back(row);
          continue;
        }
      }
      const SummaryLookup found = find_summary_metric(*run.record, th.metric);
      row.value = found.value;
      bool inconclusive = (th.wall_metric || th.wall_budget) && run.noisy;
      if (th.relative_to) {
        const RunKey* ref = reference_of(run, *th.relative_to, runs);
        const std::optional<double> reference = ref ? summary_metric(*ref->record, th.metric) : std::nullopt;
        if (ref) {
          row.reference = ref->name;
          inconclusive = inconclusive || (th.wall_metric && ref->noisy);  // its budget is none
        }
        row.value = row.value && reference && *reference != 0.0 ? std::optional(*row.value / *reference) : std::nullopt;
      }
      const bool ok = row.value && (!th.min || *row.value >= *th.min) && (!th.max || *row.value <= *th.max);
      row.verdict = !found.known ? "unknown metric"
                    : !row.value                               ? "missing"
                    : inconclusive                             ? "inconclusive"
                    : ok                                       ? "pass"
                                                               : "FAIL";
      rows.push_back(row);
    }
    if (!matched) {
      CheckRow row;
      row.threshold = &th;
      row.verdict = "missing";
      rows.push_back(row);
    }
  }
  return rows;
}

std::string format_check_rows(const std::vector<CheckRow>& rows, const std::string& thresholds_file) {
  std::string out = fmt::format("{:<14} {:<16} {:<14} {:<22} {:>12} {:>22}  {}\n", "scene", "method", "budget", "metric",
                                "value", "bound", "verdict");
  std::size_t failed = 0, inconclusive = 0;
  for (const CheckRow& r : rows) {
    const Threshold& t = *r.threshold;
    std::string metric = t.metric, value, bound;
    if (r.status_check) {  // the run's status (and reason) was what the row judged
      metric = "status";
      value = r.status.empty() ? "-" : r.status;
      bound = "= " + *t.status + (t.reason ? " \"" + *t.reason + "\"" : "");
    } else {
      value = r.value ? fmt::format("{:.6g}", *r.value) : "-";
      bound = t.min && t.max ? fmt::format("[{:.4g}, {:.4g}]", *t.min, *t.max)
              : t.min       ? fmt::format(">= {:.4g}", *t.min)
                            : fmt::format("<= {:.4g}", *t.max);
      if (t.relative_to) bound += " x " + *t.relative_to;
    }
    out += fmt::format("{:<14} {:<16} {:<14} {:<22} {:>12} {:>22}  {}", t.scene, t.method, t.budget, metric, value,
                       bound, r.verdict);
    out += t.set ? fmt::format("  set [{}]\n", fmt::join(*t.set, ", ")) : "\n";
    inconclusive += r.verdict == "inconclusive";
    failed += r.verdict != "pass" && r.verdict != "inconclusive";
  }
  out += fmt::format("{} of {} checks passed", rows.size() - failed - inconclusive, rows.size());
  if (inconclusive > 0) out += fmt::format(", {} inconclusive (measured on a noisy machine)", inconclusive);
  out += fmt::format(" ({})\n", thresholds_file);
  return out;
}

int check_exit_status(const std::vector<CheckRow>& rows, bool strict_timing) {
  bool failed = false, inconclusive = false;
  for (const CheckRow& r : rows) {
    if (r.verdict == "inconclusive") inconclusive = true;
    else if (r.verdict != "pass") failed = true;
  }
  if (failed || (inconclusive && strict_timing)) return 1;
  return inconclusive ? 4 : 0;
}

}  // namespace tcb
