#include "experiments/sweep/sweep_plan.hpp"

#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <map>
#include <set>

#include "sim/io/atomic_file.hpp"
#include "sim/io/input_error.hpp"

using namespace tcb;
namespace fs = std::filesystem;

namespace {

fs::path write_sweep(const std::string& name, const std::string& text) {
  const fs::path path = fs::temp_directory_path() / ("tcbench_sweep_" + name + "_" + std::to_string(::getpid()) + ".toml");
  write_file_atomically(path, text);
  return path;
}

}  // namespace

TEST_CASE("sweep budgets: absolute and relative labels", "[sweep]") {
  CHECK(parse_sweep_budget("none")->absolute.kind == BudgetKind::None);
  CHECK(parse_sweep_budget("ms:4.5")->absolute.value == 4.5);
  CHECK(parse_sweep_budget("work:20000")->absolute.kind == BudgetKind::Work);
  CHECK(parse_sweep_budget("full/3")->relative == SweepBudget::Relative::FullMs);
  CHECK(parse_sweep_budget("full-work/2")->divisor == 2.0);
  CHECK_FALSE(parse_sweep_budget("ms:4.5")->is_relative());
  for (const char* bad : {"", "ms:", "ms:-1", "work:1.5", "full/0", "full/x", "half", "ms:4.5x", "full-work/-2",
                          "work:2e4", "ms: 4", "ms:+4"})
    CHECK_FALSE(parse_sweep_budget(bad).has_value());
}

TEST_CASE("one budget type: BudgetSpec parses and labels its three forms", "[sweep]") {
  for (const char* label : {"none", "ms:4.5", "ms:0", "work:20000", "work:0"}) {
    INFO(label);
    REQUIRE(BudgetSpec::parse(label));
    CHECK(BudgetSpec::parse(label)->label() == label);
  }
  CHECK(BudgetSpec::parse("ms:4.5")->kind_name() == "wall_ms");
  CHECK(BudgetSpec::parse("work:7")->start().kind() == BudgetKind::Work);
  for (const char* bad : {"", "ms", "ms:nan", "ms:inf", "work:-1", "work:2.5", "full/3", "none ",
                          "work:9007199254740993", "work:9223372036854775807"})
    CHECK_FALSE(BudgetSpec::parse(bad).has_value());
  // 2^53 is the largest work budget (a double holds it and everything below exactly).
  CHECK(BudgetSpec::parse("work:9007199254740992")->label() == "work:9007199254740992");
  // Tiny and huge wall budgets are labelled without an exponent, so the label parses back.
  for (const double ms : {1e-5, 3.5e-7, 1e22, 0.1, 123456.75}) {
    INFO(ms);
    const BudgetSpec spec{BudgetKind::WallMs, ms};
    const auto again = BudgetSpec::parse(spec.label());
    REQUIRE(again.has_value());
    CHECK(again->value == Approx(ms).epsilon(1e-12));
  }
}

TEST_CASE("sweep methods: a name, or a table with the method's settings checked like a scene's", "[sweep]") {
  const fs::path path = write_sweep("methods", R"([sweep]
scenes = ["cube_drop"]
methods = ["full", { name = "every_nth", n = 4 }, { name = "every_nth", hold = false }]
budgets = ["none"]
figures = ["jitter"]
)");
  const SweepPlan plan = load_sweep_plan(path);
  REQUIRE(plan.runs.size() == 3);
  CHECK(plan.runs[1].method == "every_nth");
  CHECK(plan.runs[1].method_sets == std::vector<std::string>{"method.every_nth.n=4"});
  CHECK(plan.runs[1].id == "cube_drop-every_nth_n_4-none-s0");
  CHECK(plan.runs[2].method_sets == std::vector<std::string>{"method.every_nth.hold=false"});
  CHECK(plan.figures == std::vector<std::string>{"jitter"});
  fs::remove(path);
}

TEST_CASE("a method entry's own budgets replace the sweep's for that entry only", "[sweep]") {
  const fs::path path = write_sweep("entry_budgets", R"([sweep]
scenes = ["cube_drop"]
methods = ["interruptible", { name = "interruptible_tracked", budgets = ["full-work/3", "full-work/6"] }]
budgets = ["work:100"]
)");
  const SweepPlan plan = load_sweep_plan(path);
  std::vector<std::string> ids;
  for (const SweepRun& run : plan.runs) ids.push_back(run.id);
  // The relative budgets of the one entry bring in the reference run.
  CHECK(ids == std::vector<std::string>{"cube_drop-full-none-s0", "cube_drop-interruptible-work_100-s0",
                                        "cube_drop-interruptible_tracked-full_work_over_3-s0",
                                        "cube_drop-interruptible_tracked-full_work_over_6-s0"});
  fs::remove(path);
}

TEST_CASE("a sweep expands to scenes x sets x seeds groups, each with its reference first", "[sweep]") {
  const fs::path path = write_sweep("expand", R"([sweep]
scenes = ["cube_drop", "plates20"]
methods = ["full", "interruptible", "every_nth"]
budgets = ["none", "work:20000", "full/3"]
seeds = [0, 1]
sets = [[], ["scene.dt=0.002"]]
)");
  const SweepPlan plan = load_sweep_plan(path);
  CHECK(plan.groups == 2 * 2 * 2);
  // Per group: full once, every_nth once (no budget), interruptible x 3 budgets.
  CHECK(plan.runs.size() == 8 * 5);
  std::set<std::string> ids;
  std::map<std::string, std::size_t> position;
  for (std::size_t i = 0; i < plan.runs.size(); ++i) {
    ids.insert(plan.runs[i].id);
    position[plan.runs[i].id] = i;
  }
  CHECK(ids.size() == plan.runs.size());
  for (const SweepRun& run : plan.runs) {
    if (!run.budget.is_relative()) continue;
    REQUIRE(position.count(run.reference_id));
    const SweepRun& reference = plan.runs[position[run.reference_id]];
    CHECK(position[run.reference_id] < position[run.id]);
    CHECK(reference.method == "full");
    CHECK(reference.group == run.group);
  }
  fs::remove(path);
}

TEST_CASE("quick_seeds: reproduce --quick keeps the first N seeds' runs, whole groups", "[sweep]") {
  const fs::path path = write_sweep("quick_seeds", R"([sweep]
scenes = ["cube_drop"]
methods = ["full", "interruptible"]
budgets = ["full-work/2"]
seeds = [4, 5, 6, 7, 8]
quick_seeds = 2
sets = [["perturb.velocity=1e-3"]]
)");
  const SweepPlan plan = load_sweep_plan(path);
  CHECK(plan.runs.size() == 10);  // 5 seeds x (reference full + interruptible)
  CHECK(plan.seeds == std::vector<std::uint64_t>{4, 5, 6, 7, 8});
  const SweepPlan quick = quick_plan(plan);
  REQUIRE(quick.runs.size() == 4);
  for (const SweepRun& run : quick.runs) CHECK((run.seed == 4 || run.seed == 5));
  CHECK(quick.seeds == std::vector<std::uint64_t>{4, 5});
  fs::remove(path);
  const fs::path all = write_sweep("quick_all", "[sweep]\nscenes = [\"cube_drop\"]\nmethods = [\"full\"]\nbudgets = [\"none\"]\nseeds = [0, 1]\n");
  CHECK(quick_plan(load_sweep_plan(all)).runs.size() == 2);  // no quick_seeds: all seeds
  fs::remove(all);
}

TEST_CASE("shards cover every run exactly once, whole groups each", "[sweep]") {
  const fs::path path = write_sweep("shard", R"([sweep]
scenes = ["cube_drop", "plates20"]
methods = ["full", "interruptible"]
budgets = ["full-work/2", "work:100"]
seeds = [0, 1, 2]
)");
  const SweepPlan plan = load_sweep_plan(path);
  for (std::size_t n = 1; n <= 7; ++n) {
    std::map<std::string, int> seen;
    std::map<std::size_t, std::size_t> shard_of_group;
    for (std::size_t i = 0; i < n; ++i)
      for (const SweepRun& run : shard_runs(plan, i, n)) {
        ++seen[run.id];
        if (shard_of_group.count(run.group)) CHECK(shard_of_group[run.group] == i);
        shard_of_group[run.group] = i;
      }
    CHECK(seen.size() == plan.runs.size());
    for (const auto& [id, count] : seen) CHECK(count == 1);
  }
  CHECK(parse_shard("2/4") == std::pair<std::size_t, std::size_t>{2, 4});
  for (const char* bad : {"4/4", "-1/4", "1", "1/0", "a/b", "1/4x"}) CHECK_THROWS_AS(parse_shard(bad), InputError);
  fs::remove(path);
}

TEST_CASE("malformed sweep files are rejected with the file and the line", "[sweep]") {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"[sweep]\nscenes = [\"cube_drop\"]\nmethods = [\"full\"]\nbudgets = [\"fast\"]\n", ":4: sweep.budgets"},
      {"[sweep]\nscenes = [\"cube_drop\"]\nmethods = [\"nope\"]\nbudgets = [\"none\"]\n", ":3: sweep.methods"},
      {"[sweep]\nscenes = [\"no_such_scene\"]\nmethods = [\"full\"]\nbudgets = [\"none\"]\n", ":2: sweep.scenes"},
      {"[sweep]\nscenes = [\"cube_drop\"]\nmethods = [\"full\"]\nbudgets = [\"none\"]\nspeed = 3\n", ":5: unknown key"},
      {"[sweep]\nscenes = []\nmethods = [\"full\"]\nbudgets = [\"none\"]\n", ":2: sweep.scenes"},
      {"[sweep]\nscenes = [\"cube_drop\"\n", ":"},
      {"[other]\n", "missing the [sweep] table"},
      {"[sweep]\nscenes = [\"cube_drop\"]\nmethods = [{ name = \"every_nth\", n = 0 }]\nbudgets = [\"none\"]\n",
       ":3: methods[0].n: must lie in"},
      {"[sweep]\nscenes = [\"cube_drop\"]\nmethods = [{ name = \"every_nth\", m = 1 }]\nbudgets = [\"none\"]\n",
       ":3: unknown key 'm'"},
      {"[sweep]\nscenes = [\"cube_drop\"]\nmethods = [\"every_nth\", { name = \"every_nth\", n = 2 }]\nbudgets = [\"none\"]\n",
       ":3: sweep.methods: entry 1 repeats an earlier one"},
      {"[sweep]\nscenes = [\"cube_drop\"]\nmethods = [{ name = \"interruptible\", budgets = [\"fast\"] }]\nbudgets = "
       "[\"none\"]\n",
       ":3: methods[0].budgets: 'fast' is not"},
      {"[sweep]\nscenes = [\"cube_drop\"]\nmethods = [\"full\"]\nbudgets = [\"none\"]\nfigures = [\"fig99\"]\n",
       ":5: sweep.figures: no report figure 'fig99'"},
      {"[sweep]\nscenes = [\"cube_drop\"]\nmethods = [\"full\"]\nbudgets = [\"none\"]\ndivergence = 10\n"
       "sets = [[\"perturb.position=1e-3\"]]\n",
       ":6: sweep.sets: \"perturb.position=1e-3\" with divergence"},
      {"[sweep]\nscenes = [\"cube_drop\"]\nmethods = [\"full\"]\nbudgets = [\"none\"]\nquick_seeds = 0\n",
       ":5: sweep.quick_seeds"},
  };
  for (const auto& [text, expected] : cases) {
    INFO(text);
    const fs::path path = write_sweep("bad", text);
    try {
      load_sweep_plan(path);
      FAIL("accepted");
    } catch (const InputError& e) {
      CHECK_THAT(std::string(e.what()), Catch::Matchers::Contains(path.string()));
      CHECK_THAT(std::string(e.what()), Catch::Matchers::Contains(expected));
    }
    fs::remove(path);
  }
}

TEST_CASE("divergence: every group gets its full reference, a noise-floor run, and every run waits for it", "[sweep]") {
  const fs::path path = write_sweep("divergence", R"([sweep]
scenes = ["cube_drop"]
methods = ["every_nth", "interruptible"]
budgets = ["work:100"]
seeds = [0, 1]
divergence = 5
noise_floor = 2e-9
)");
  const SweepPlan plan = load_sweep_plan(path);
  CHECK(plan.divergence_every == 5);
  CHECK(plan.noise_floor_m == 2e-9);
  std::size_t floors = 0;
  for (const SweepRun& run : plan.runs) {
    INFO(run.id);
    const bool reference = run.method == "full" && run.reference_id.empty();
    if (reference) continue;
    CHECK_FALSE(run.reference_id.empty());  // compared with its group's full run
    const auto at = std::find_if(plan.runs.begin(), plan.runs.end(), [&](const SweepRun& r) { return r.id == run.reference_id; });
    REQUIRE(at != plan.runs.end());
    CHECK(at->group == run.group);
    CHECK(at - plan.runs.begin() < &run - plan.runs.data());  // the reference comes first
    if (run.id.find("noise_floor") != std::string::npos) {
      ++floors;
      CHECK(run.method == "full");
      CHECK(run.sets == std::vector<std::string>{"perturb.position=2e-09"});
    }
  }
  CHECK(floors == 2);
  CHECK(plan.runs.size() == 2 * 4);  // per seed: full, its noise floor, every_nth, interruptible
  fs::remove(path);
  const fs::path off = write_sweep("divergence_off", "[sweep]\nscenes = [\"cube_drop\"]\nmethods = [\"every_nth\"]\nbudgets = [\"none\"]\n");
  const SweepPlan without = load_sweep_plan(off);
  REQUIRE(without.runs.size() == 1);
  CHECK(without.runs[0].reference_id.empty());
  fs::remove(off);
  const fs::path bad = write_sweep("divergence_bad", "[sweep]\nscenes = [\"cube_drop\"]\nmethods = [\"full\"]\nbudgets = [\"none\"]\ndivergence = 0\n");
  CHECK_THROWS_AS(load_sweep_plan(bad), InputError);
  fs::remove(bad);
}
