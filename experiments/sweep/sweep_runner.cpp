#include "experiments/sweep/sweep_runner.hpp"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <deque>
#include <map>
#include <stdexcept>

#include "experiments/results/configurations_csv.hpp"
#include "experiments/results/summary_csv.hpp"
#include "experiments/run/thread_clock.hpp"
#include "experiments/sweep/directory_lock.hpp"
#include "sim/io/input_error.hpp"
#include "sim/io/atomic_file.hpp"

namespace tcb {
namespace {

namespace fs = std::filesystem;

// The absolute budget arguments of a run, or an error when its reference
// has no usable figure.
std::vector<std::string> budget_args(const SweepRun& run, const fs::path& runs_dir, std::string& error) {
  const SweepBudget& b = run.budget;
  if (!b.is_relative()) {
    switch (b.absolute.kind) {
      case BudgetKind::None: return {};
      case BudgetKind::WallMs: return {"--budget-ms", plain_decimal(b.absolute.value)};
      case BudgetKind::Work:
        return {"--budget-work", fmt::format("{}", static_cast<std::uint64_t>(b.absolute.value))};
    }
  }
  const auto reference = read_complete_run(runs_dir / run.reference_id);
  if (!reference || (*reference)["status"] != "ok") {
    error = "its reference run " + run.reference_id + " did not complete";
    return {};
  }
  if (b.relative == SweepBudget::Relative::FullMs) {
    const auto p50 = summary_metric(*reference, "handling_ms.p50");
    if (!p50) {
      error = "reference has no handling_ms.p50";
      return {};
    }
    return {"--budget-ms", plain_decimal(std::stod(fmt::format("{:.6g}", *p50 / b.divisor)))};
  }
  const auto total = summary_metric(*reference, "work_units_total");
  const double steps = (*reference)["steps"].get<double>();
  if (!total || steps <= 0) {
    error = "reference has no work_units_total";
    return {};
  }
  const auto per_step = static_cast<std::uint64_t>(std::max(1.0, std::floor(*total / steps / b.divisor)));
  return {"--budget-work", fmt::format("{}", per_step)};
}

pid_t start(const SweepPlan& plan, const SweepRun& run, const SweepOptions& options, std::vector<std::string> args) {
  const fs::path dir = options.out_dir / "runs" / run.id;
  std::vector<std::string> argv = {options.executable.string(), "run", run.scene, "--method", run.method,
                                   "--seed", std::to_string(run.seed), "--out", dir.string(), "--quiet",
                                   "--oracle", plan.oracle, "--budget-label", run.budget.label,
                                   "--force-reference", plan.force_reference};
  argv.insert(argv.end(), args.begin(), args.end());
  if (plan.divergence_every > 0) {
    if (run.reference_id.empty() && run.method == "full" && !run.budget.is_relative() &&
        run.budget.absolute.kind == BudgetKind::None)
      argv.insert(argv.end(), {"--trajectory", std::to_string(plan.divergence_every)});
    else if (!run.reference_id.empty())
      argv.insert(argv.end(), {"--reference", (options.out_dir / "runs" / run.reference_id).string()});
  }
  if (plan.oracle_volume) argv.insert(argv.end(), {"--oracle-volume", *plan.oracle_volume});
  const auto steps = options.quick && plan.quick_steps ? plan.quick_steps : plan.steps;
  if (steps) argv.insert(argv.end(), {"--steps", std::to_string(*steps)});
  if (plan.record > 0) argv.insert(argv.end(), {"--record", std::to_string(plan.record)});
  for (const auto& s : run.sets) argv.insert(argv.end(), {"--set", s});
  for (const auto& s : run.method_sets) argv.insert(argv.end(), {"--set", s});
  const std::string log = (dir / "log.txt").string();
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      dup2(fd, 1);
      dup2(fd, 2);
      close(fd);
    }
    std::vector<char*> c;
    for (auto& a : argv) c.push_back(a.data());
    c.push_back(nullptr);
    execv(c[0], c.data());
    _exit(127);
  }
  return pid;
}

// DIR/sweep.json: what the report needs of the plan (which figures its runs feed).
void write_sweep_json(const SweepPlan& plan, const fs::path& out_dir) {
  nlohmann::ordered_json sweep;
  sweep["schema"] = "tcbench.sweep/1";
  sweep["file"] = plan.file.string();
  sweep["description"] = plan.description;
  sweep["figures"] = plan.figures;
  sweep["seeds"] = plan.seeds;
  sweep["runs"] = nlohmann::ordered_json::array();
  for (const SweepRun& run : plan.runs) sweep["runs"].push_back("runs/" + run.id);
  write_file_atomically(out_dir / "sweep.json", sweep.dump(2) + "\n");
}

}  // namespace

SweepOutcome run_sweep(const SweepPlan& plan, const SweepOptions& options) {
  const fs::path runs_dir = options.out_dir / "runs";
  fs::create_directories(runs_dir);
  const std::vector<SweepRun> runs = shard_runs(plan, options.shard_index, options.shard_count);
  SweepOutcome outcome;
  outcome.total = runs.size();
  std::map<std::string, std::string> status;  // run id -> status in this invocation
  std::deque<SweepRun> pending;
  std::size_t done = 0;
  const auto finish = [&](const SweepRun& run, const std::string& s) {
    status[run.id] = s;
    if (s == "ok") ++outcome.ok;
    else if (s == "unstable") ++outcome.unstable;
    else if (s == "skipped") ++outcome.skipped;
    else ++outcome.failed;
    ++done;
    if (options.on_run) options.on_run(done, outcome.total, run, s);
  };
  for (const SweepRun& run : runs) {
    if (options.resume && read_complete_run(runs_dir / run.id)) {
      finish(run, "skipped");
      continue;
    }
    fs::remove_all(runs_dir / run.id);  // a half-written earlier attempt, or a rerun
    pending.push_back(run);
  }
  std::map<pid_t, SweepRun> running;
  std::map<pid_t, int> running_cpu;  // with pin_cpus: the CPU each running run holds
  const auto free_cpu = [&]() {
    for (const int cpu : options.pin_cpus)
      if (std::none_of(running_cpu.begin(), running_cpu.end(), [&](const auto& r) { return r.second == cpu; }))
        return cpu;
    return -1;
  };
  const auto reference_done = [&](const SweepRun& run) {
    if (run.reference_id.empty()) return true;
    const bool ours = std::any_of(running.begin(), running.end(), [&](const auto& r) { return r.second.id == run.reference_id; }) ||
                      std::any_of(pending.begin(), pending.end(), [&](const SweepRun& p) { return p.id == run.reference_id; });
    return !ours;
  };
  while (!pending.empty() || !running.empty()) {
    bool started = false;
    for (auto it = pending.begin(); it != pending.end() && running.size() < std::max<std::size_t>(1, options.jobs);) {
      if (!reference_done(*it)) {
        ++it;
        continue;
      }
      const SweepRun run = *it;
      it = pending.erase(it);
      std::string error;
      auto args = budget_args(run, runs_dir, error);
      const int cpu = options.pin_cpus.empty() ? -1 : free_cpu();
      if (cpu >= 0) args.insert(args.end(), {"--pin", std::to_string(cpu)});
      if (!error.empty()) {
        fs::create_directories(runs_dir / run.id);
        write_file_atomically(runs_dir / run.id / "log.txt", "not started: " + error + "\n");
        finish(run, "failed");
        continue;
      }
      fs::create_directories(runs_dir / run.id);
      const pid_t pid = start(plan, run, options, args);
      running[pid] = run;
      if (cpu >= 0) running_cpu[pid] = cpu;
      started = true;
    }
    if (running.empty()) {
      if (!started && !pending.empty()) {  // cannot happen: references precede their runs
        for (const auto& run : pending) finish(run, "failed");
        pending.clear();
      }
      continue;
    }
    int wstatus = 0;
    const pid_t pid = waitpid(-1, &wstatus, 0);
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    const SweepRun run = it->second;
    running.erase(it);
    running_cpu.erase(pid);
    const int code = WIFEXITED(wstatus) ? WEXITSTATUS(wstatus) : -1;
    finish(run, code == 0 ? "ok" : code == 1 && read_complete_run(runs_dir / run.id) ? "unstable" : "failed");
  }

  // Shards sharing DIR write the summary one at a time; see directory_lock.hpp.
  const DirectoryLock lock(options.out_dir);
  std::vector<SummaryRow> rows;
  for (const SweepRun& run : plan.runs) {
    SummaryRow row{run.id, read_complete_run(runs_dir / run.id), "missing"};
    if (!row.record && status.count(run.id)) row.status = status[run.id];
    rows.push_back(std::move(row));
  }
  write_summary_csv(options.out_dir / "summary.csv", rows);
  std::vector<CollectedRun> complete;
  for (const SweepRun& run : plan.runs)
    if (auto record = read_complete_run(runs_dir / run.id))
      complete.push_back({"runs/" + run.id, runs_dir / run.id, std::move(*record)});
  write_configurations_csv(options.out_dir / "configurations.csv", complete);
  write_sweep_json(plan, options.out_dir);
  return outcome;
}

std::vector<int> parse_pin_cpus(const std::string& text, std::size_t jobs) {
  const std::vector<int> allowed = allowed_cpus();
  std::vector<int> cpus;
  if (text == "auto") {
    cpus.assign(allowed.rbegin(), allowed.rend());
  } else {
    std::size_t start = 0;
    while (start <= text.size()) {
      const std::size_t comma = std::min(text.find(',', start), text.size());
      const std::string item = text.substr(start, comma - start);
      std::size_t used = 0;
      int cpu = -1;
      try {
        cpu = std::stoi(item, &used);
      } catch (const std::exception&) {
      }
      if (item.empty() || used != item.size() || cpu < 0)
        throw InputError("--pin", 0, "expected auto or a list of CPU numbers like 2,3, not '" + text + "'");
      if (std::find(allowed.begin(), allowed.end(), cpu) == allowed.end())
        throw InputError("--pin", 0, "CPU " + item + " is not one this process may use (" +
                                         std::to_string(allowed.size()) + " allowed)");
      if (std::find(cpus.begin(), cpus.end(), cpu) != cpus.end())
        throw InputError("--pin", 0, "CPU " + item + " is listed twice: each job needs its own CPU");
      cpus.push_back(cpu);
      start = comma + 1;
    }
  }
  if (cpus.size() < jobs)
    throw InputError("--pin", 0, fmt::format("{} jobs need {} CPUs to pin to, '{}' gives {}", jobs, jobs, text,
                                             cpus.size()));
  cpus.resize(jobs);
  return cpus;
}

}  // namespace tcb
