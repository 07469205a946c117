#include "experiments/sweep/sweep_plan.hpp"

#include <fmt/format.h>

#include <map>
#include <sstream>

#include "baselines/registry.hpp"
#include "experiments/run/run_scene.hpp"
#include "experiments/scene/scene_file.hpp"
#include "experiments/run/provenance.hpp"
#include "experiments/scene/method_settings_reader.hpp"
#include "experiments/scene/toml_table_reader.hpp"

namespace tcb {
namespace {

std::string id_part(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_') out += c;
    else if (c == '/') out += "_over_";
    else out += '_';
  }
  return out;
}

// Budget labels of `key`, each one checked (TableReader::fail names the key's line).
std::vector<SweepBudget> parse_budgets(TableReader& reader, std::string_view key,
                                       const std::vector<std::string>& labels) {
  std::vector<SweepBudget> out;
  for (const auto& label : labels) {
    const auto b = parse_sweep_budget(label);
    if (!b) reader.fail(key, "'" + label + "' is not none, ms:X, work:N (whole), full/K or full-work/K (K > 0)");
    out.push_back(*b);
  }
  return out;
}

}  // namespace

std::optional<SweepBudget> parse_sweep_budget(const std::string& label) {
  SweepBudget b;
  b.label = label;
  const auto relative = [&](std::size_t prefix, SweepBudget::Relative kind) -> std::optional<SweepBudget> {
    const auto k = parse_budget_number(label.substr(prefix));
    if (!k || !(*k > 0.0)) return std::nullopt;
    b.relative = kind;
    b.divisor = *k;
    return b;
  };
  if (label.rfind("full-work/", 0) == 0) return relative(10, SweepBudget::Relative::FullWork);
  if (label.rfind("full/", 0) == 0) return relative(5, SweepBudget::Relative::FullMs);
  const auto absolute = BudgetSpec::parse(label);
  if (!absolute) return std::nullopt;
  b.absolute = *absolute;
  b.label = absolute->label();  // one spelling: "ms:4.50" is recorded as "ms:4.5"
  return b;
}

// The plan of a parsed sweep file (below).
static SweepPlan sweep_plan_of(const toml::table& root, const std::filesystem::path& path);

SweepPlan load_sweep_plan(const std::filesystem::path& path) { return sweep_plan_of(parse_toml_file(path), path); }

SweepPlan parse_sweep_plan(std::string_view text, const std::filesystem::path& path) {
  return sweep_plan_of(parse_toml_text(text, path), path);
}

static SweepPlan sweep_plan_of(const toml::table& root, const std::filesystem::path& path) {
  const Origins origins{path.string(), {}};
  TableReader top(root, "sweep file", origins);
  const toml::table* table = top.table("sweep");
  if (!table) throw InputError(path.string(), 1, "missing the [sweep] table");
  top.finish();
  TableReader r(*table, "sweep", origins);
  SweepPlan plan;
  plan.file = path;
  plan.description = r.string("description").value_or("");
  const auto need = [&](std::string_view key) {
    auto list = r.string_list(key);
    if (!list || list->empty()) r.fail(key, "must list at least one entry");
    return *list;
  };
  const std::vector<std::string> scenes = need("scenes"), budget_labels = need("budgets");
  for (const auto& scene : scenes) {
    try {
      resolve_scene(scene, default_scene_dirs());
    } catch (const InputError& e) {
      r.fail("scenes", e.what());
    }
  }
  const std::vector<SweepBudget> budgets = parse_budgets(r, "budgets", budget_labels);
  std::map<std::string, bool> uses_budget;
  // A method entry is a registry name, or a table { name = "every_nth", n = 4 }
  // whose other keys are the method's settings, checked against its schema
  // exactly as a scene's [method.every_nth] table is.
  struct MethodEntry {
    std::string name, id;
    std::vector<std::string> sets;
    std::vector<SweepBudget> budgets;  ///< its own `budgets`, else the sweep's
  };
  std::vector<MethodEntry> entries;
  const toml::node* methods = r.node("methods");
  const toml::array* method_list = methods ? methods->as_array() : nullptr;
  if (!method_list || method_list->empty())
    r.fail("methods", "must list at least one method: a name or { name = \"NAME\", setting = value }");
  for (std::size_t i = 0; i < method_list->size(); ++i) {
    const toml::node& entry = (*method_list)[i];
    MethodEntry e;
    const MethodInfo* info = nullptr;
    const auto lookup = [&](const std::string& name) {
      for (const MethodInfo& m : method_registry())
        if (m.name == name) return &m;
      r.fail("methods", "unknown method '" + name + "' (see `tcbench list methods`)");
    };
    if (entry.is_string()) {
      e.name = e.id = *entry.value<std::string>();
      info = lookup(e.name);
    } else if (const toml::table* t = entry.as_table()) {
      TableReader mr(*t, "methods[" + std::to_string(i) + "]", origins);
      const auto name = mr.string("name");
      if (!name) mr.fail("name", "names the method: { name = \"every_nth\", n = 4 }");
      e.name = e.id = *name;
      info = lookup(e.name);
      const MethodSettings settings = read_method_settings(mr, *info);
      if (const auto labels = mr.string_list("budgets")) {
        if (labels->empty()) mr.fail("budgets", "must list at least one budget");
        e.budgets = parse_budgets(mr, "budgets", *labels);
      }
      mr.finish();
      for (const SettingSpec& spec : info->settings) {  // what differs from the defaults, in schema order
        const SettingValue& value = settings.values().at(spec.name);
        if (value == spec.default_value) continue;  // as the run's method_label leaves it out
        const std::string text = format_setting(value);
        e.sets.push_back("method." + e.name + "." + spec.name + "=" + text);
        e.id += '_';
        e.id += id_part(spec.name + "=" + text);
      }
    } else {
      r.fail("methods", "each entry is a method name or { name = \"NAME\", setting = value }");
    }
    for (const MethodEntry& earlier : entries)  // the same label twice could not be told apart in results
      if (earlier.id == e.id)
        r.fail("methods", "entry " + std::to_string(i) + " repeats an earlier one (same method, same settings)");
    uses_budget[e.id] = info->uses_budget;
    if (e.budgets.empty()) e.budgets = budgets;
    entries.push_back(e);
  }
  std::vector<std::uint64_t> seeds{0};
  if (const toml::node* n = r.node("seeds")) {
    const toml::array* a = n->as_array();
    if (!a || a->empty()) r.fail("seeds", "must be an array of whole numbers >= 0");
    seeds.clear();
    for (const auto& e : *a) {
      if (!e.is_integer() || *e.value<std::int64_t>() < 0) r.fail("seeds", "must be an array of whole numbers >= 0");
      seeds.push_back(static_cast<std::uint64_t>(*e.value<std::int64_t>()));
    }
  }
  plan.seeds = seeds;
  if (const auto n = r.integer("quick_seeds", 1, std::int64_t{1} << 20)) plan.quick_seeds = static_cast<std::size_t>(*n);
  plan.steps = r.integer("steps", 1, std::int64_t{1} << 40);
  plan.quick_steps = r.integer("quick_steps", 1, std::int64_t{1} << 40);
  plan.record = static_cast<int>(r.integer("record", 1, 1 << 30).value_or(0));
  plan.oracle = r.string("oracle").value_or("off");
  try {
    parse_oracle_schedule(plan.oracle);
  } catch (const InputError& e) {
    r.fail("oracle", e.what());
  }
  plan.oracle_volume = r.string("oracle_volume");
  if (plan.oracle_volume) {
    try {
      parse_oracle_schedule(*plan.oracle_volume, "oracle_volume");
    } catch (const InputError& e) {
      r.fail("oracle_volume", e.what());
    }
  }
  plan.force_reference = r.string("force_reference").value_or("off");
  try {
    parse_oracle_schedule(plan.force_reference, "force_reference");
  } catch (const InputError& e) {
    r.fail("force_reference", e.what());
  }
  plan.divergence_every = static_cast<int>(r.integer("divergence", 1, 1 << 30).value_or(0));
  plan.noise_floor_m = r.non_negative("noise_floor", plan.noise_floor_m);
  std::vector<std::vector<std::string>> sets{{}};
  if (const toml::node* n = r.node("sets")) {
    const toml::array* a = n->as_array();
    if (!a || a->empty()) r.fail("sets", "must be an array of arrays of \"key=value\" strings");
    sets.clear();
    for (const auto& e : *a) {
      const toml::array* inner = e.as_array();
      if (!inner) r.fail("sets", "must be an array of arrays of \"key=value\" strings");
      std::vector<std::string> set;
      for (const auto& s : *inner) {
        if (!s.is_string()) r.fail("sets", "must be an array of arrays of \"key=value\" strings");
        set.push_back(*s.value<std::string>());
      }
      sets.push_back(set);
    }
  }
  // The noise-floor run sets [perturb] position to the floor: a set that
  // jitters positions itself would have its jitter replaced there, and the
  // floor would no longer be the reference nudged by noise_floor.
  if (plan.divergence_every > 0 && plan.noise_floor_m > 0.0)
    for (const auto& set : sets)
      for (const std::string& o : set)
        if (o.rfind("perturb.position=", 0) == 0)
          r.fail("sets", "\"" + o + "\" with divergence: the noise-floor run replaces [perturb] position; "
                         "jitter by velocity, rotation or material instead (or noise_floor = 0)");
  if (const auto figures = r.string_list("figures")) {
    for (const std::string& figure : *figures)
      if (!std::filesystem::exists(source_tree_dir() / "report" / "tcbench_report" / "figures" / (figure + ".py")))
        r.fail("figures", "no report figure '" + figure + "' (report/tcbench_report/figures/" + figure + ".py)");
    plan.figures = *figures;
  }
  r.finish();

  bool any_relative = false;
  for (const MethodEntry& e : entries)
    for (const SweepBudget& b : e.budgets) any_relative = any_relative || b.is_relative();
  std::map<std::string, std::size_t> seen;
  for (const auto& scene : scenes)
    for (std::size_t s = 0; s < sets.size(); ++s)
      for (std::size_t seed_index = 0; seed_index < seeds.size(); ++seed_index) {
        const std::uint64_t seed = seeds[seed_index];
        const std::size_t group = plan.groups++;
        const std::string tail =
            fmt::format("-s{}", seed) + (sets.size() > 1 ? fmt::format("-v{}", s) : std::string());
        const auto add = [&](const MethodEntry& method, const SweepBudget& budget, const std::string& reference) {
          SweepRun run{id_part(scene) + "-" + method.id + "-" + id_part(budget.label) + tail,
                       scene,
                       method.name,
                       method.sets,
                       budget,
                       seed,
                       s,
                       sets[s],
                       group,
                       seed_index,
                       reference};
          if (seen.count(run.id)) return;
          seen[run.id] = plan.runs.size();
          plan.runs.push_back(run);
        };
        const std::string reference_id = id_part(scene) + "-full-none" + tail;
        const bool diverge = plan.divergence_every > 0;
        // The reference comes first; with divergence every run but it is compared with it.
        if (any_relative || diverge) add(MethodEntry{"full", "full", {}, {}}, SweepBudget{}, "");
        if (diverge && plan.noise_floor_m > 0.0) {
          SweepRun floor{id_part(scene) + "-full-none-noise_floor" + tail, scene, "full", {}, SweepBudget{}, seed, s,
                         sets[s], group, seed_index, reference_id};
          floor.sets.push_back(fmt::format("perturb.position={}", plan.noise_floor_m));
          seen[floor.id] = plan.runs.size();
          plan.runs.push_back(floor);
        }
        for (const MethodEntry& method : entries)
          for (const auto& budget : method.budgets) {
            if (!uses_budget[method.id]) {
              add(method, SweepBudget{}, diverge ? reference_id : "");
              continue;
            }
            add(method, budget, budget.is_relative() || diverge ? reference_id : "");
          }
      }
  return plan;
}

SweepPlan quick_plan(SweepPlan plan) {
  if (!plan.quick_seeds || *plan.quick_seeds >= plan.seeds.size()) return plan;
  std::erase_if(plan.runs, [&](const SweepRun& run) { return run.seed_index >= *plan.quick_seeds; });
  plan.seeds.resize(*plan.quick_seeds);
  return plan;
}

std::vector<SweepRun> shard_runs(const SweepPlan& plan, std::size_t index, std::size_t count) {
  std::vector<SweepRun> out;
  for (const SweepRun& run : plan.runs)
    if (run.group % count == index) out.push_back(run);
  return out;
}

std::pair<std::size_t, std::size_t> parse_shard(const std::string& text) {
  const auto slash = text.find('/');
  try {
    if (slash != std::string::npos) {
      std::size_t a = 0, b = 0;
      const long long i = std::stoll(text.substr(0, slash), &a), n = std::stoll(text.substr(slash + 1), &b);
      if (a == slash && b == text.size() - slash - 1 && n >= 1 && i >= 0 && i < n)
        return {static_cast<std::size_t>(i), static_cast<std::size_t>(n)};
    }
  } catch (const std::exception&) {
  }
  throw InputError("--shard", 0, "expected I/N with 0 <= I < N (e.g. 0/4), not '" + text + "'");
}

}  // namespace tcb
