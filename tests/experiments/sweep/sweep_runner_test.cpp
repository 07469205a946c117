// A sweep killed halfway (SIGKILL to the sweep and its runs) and resumed ends
// with every run present exactly once and nothing half-written.
#include "experiments/sweep/sweep_runner.hpp"

#include <catch2/catch.hpp>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <thread>

#include "experiments/results/summary_csv.hpp"
#include <nlohmann/json.hpp>
#include "experiments/run/thread_clock.hpp"
#include "sim/io/atomic_file.hpp"
#include "sim/io/input_error.hpp"

using namespace tcb;
namespace fs = std::filesystem;

TEST_CASE("a sweep killed halfway and resumed has every run exactly once, none half-written", "[sweep][slow]") {
  const fs::path root = fs::temp_directory_path() / ("tcbench_sweep_resume_" + std::to_string(::getpid()));
  fs::remove_all(root);
  fs::create_directories(root);
  const fs::path file = root / "sweep.toml", out = root / "out";
  write_file_atomically(file, R"([sweep]
scenes = ["cube_drop"]
methods = ["full", "interruptible"]
budgets = ["work:20000", "full-work/2"]
seeds = [0, 1, 2]
steps = 400
figures = ["jitter"]
)");
  const SweepPlan plan = load_sweep_plan(file);
  REQUIRE(plan.runs.size() == 9);

  // Start the sweep as its own process group, kill the group once some runs are complete.
  const pid_t pid = fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    setpgid(0, 0);
    const int devnull = ::open("/dev/null", O_WRONLY);
    dup2(devnull, 2);
    dup2(devnull, 1);
    execl(TCBENCH_EXE, TCBENCH_EXE, "sweep", file.c_str(), "--out", out.c_str(), "--jobs", "2", nullptr);
    _exit(127);
  }
  setpgid(pid, pid);
  const auto complete = [&] {
    int n = 0;
    for (const SweepRun& run : plan.runs) n += read_complete_run(out / "runs" / run.id).has_value();
    return n;
  };
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (complete() < 3 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ::kill(-pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  const int before = complete();
  INFO("complete runs when killed: " << before);
  CHECK(before >= 3);
  CHECK(before < 9);  // really halfway
  CHECK_FALSE(fs::exists(out / "summary.csv"));

  SweepOptions options;
  options.out_dir = out;
  options.executable = TCBENCH_EXE;
  options.jobs = 2;
  options.resume = true;
  const SweepOutcome outcome = run_sweep(plan, options);
  CHECK(outcome.skipped == static_cast<std::size_t>(before));
  CHECK(outcome.ok == 9 - outcome.skipped);
  CHECK(outcome.failed == 0);
  CHECK(complete() == 9);
  int dirs = 0;
  for (const auto& entry : fs::directory_iterator(out / "runs")) {
    ++dirs;
    CHECK(read_complete_run(entry.path()).has_value());
  }
  CHECK(dirs == 9);
  for (const auto& entry : fs::recursive_directory_iterator(out)) CHECK(entry.path().extension() != ".tmp");
  // summary.csv: a header and one row per run, each present once, each ok.
  std::ifstream csv(out / "summary.csv");
  std::vector<std::string> lines;
  for (std::string line; std::getline(csv, line);) lines.push_back(line);
  REQUIRE(lines.size() == 10);
  for (const SweepRun& run : plan.runs) {
    const auto n = std::count_if(lines.begin(), lines.end(), [&](const std::string& l) { return l.rfind(run.id + ",", 0) == 0; });
    CHECK(n == 1);
  }
  // configurations.csv: the three configurations, each resting on its three seeds.
  std::ifstream conf(out / "configurations.csv");
  std::vector<std::string> conf_lines;
  for (std::string line; std::getline(conf, line);) conf_lines.push_back(line);
  REQUIRE(conf_lines.size() == 4);
  CHECK(conf_lines[0].rfind("configuration,scene,method,budget,response,overrides,runs,seeds,unstable,", 0) == 0);
  for (std::size_t i = 1; i < conf_lines.size(); ++i) CHECK(conf_lines[i].find(",3,0 1 2,0,3,0,") != std::string::npos);
  // A relative budget recorded both forms.
  const auto relative = read_complete_run(out / "runs" / "cube_drop-interruptible-full_work_over_2-s0");
  REQUIRE(relative);
  CHECK((*relative)["budget"]["label"] == "full-work/2");
  CHECK((*relative)["budget"]["kind"] == "work");
  CHECK((*relative)["budget"]["value"].get<double>() >= 1.0);
  // sweep.json tells the report which runs the sweep made and which figures they feed.
  const auto sweep = nlohmann::json::parse(read_file(out / "sweep.json"));
  CHECK(sweep["schema"] == "tcbench.sweep/1");
  CHECK(sweep["figures"] == nlohmann::json::array({"jitter"}));
  REQUIRE(sweep["runs"].size() == 9);
  for (const auto& run : sweep["runs"]) CHECK(read_complete_run(out / run.get<std::string>()).has_value());
  fs::remove_all(root);
}

TEST_CASE("pinning CPUs for sweeps: auto gives the allowed ones highest first; lists are checked", "[sweep][pin]") {
  const std::vector<int> allowed = allowed_cpus();
  REQUIRE(!allowed.empty());
  const std::vector<int> one = parse_pin_cpus("auto", 1);
  CHECK(one == std::vector<int>{allowed.back()});  // away from CPU 0 where there is a choice
  CHECK(parse_pin_cpus(std::to_string(allowed.front()), 1) == std::vector<int>{allowed.front()});
  const auto rejects = [](const std::string& text, std::size_t jobs, const std::string& why) {
    INFO(text);
    try {
      parse_pin_cpus(text, jobs);
      FAIL("accepted");
    } catch (const InputError& e) {
      CHECK_THAT(std::string(e.what()), Catch::Matchers::Contains(why));
    }
  };
  rejects("", 1, "expected auto or a list");
  rejects("1,x", 1, "expected auto or a list");
  rejects("-1", 1, "expected auto or a list");
  rejects("99999", 1, "is not one this process may use");
  rejects("auto", allowed.size() + 1, "CPUs to pin to");
  const std::string cpu = std::to_string(allowed.front());
  rejects(cpu + "," + cpu, 1, "listed twice");
}
