// tcbench compare on crafted results: two copies of one folder differ in
// nothing and pass every threshold; a slower, less accurate candidate breaks
// its thresholds; a timing change that is not significant does not; pairing,
// unpaired configurations, unknown metrics and malformed limits; and the
// command's exit statuses (0, 1, 2) from the real binary.
#include "experiments/compare/compare_results.hpp"

#include <catch2/catch.hpp>
#include <unistd.h>

#include <cstdlib>
#include <fstream>

#include "sim/io/input_error.hpp"

using namespace tcb;
namespace fs = std::filesystem;

namespace {

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("tcbench_compare_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// A run as tcbench writes it, reduced to what compare reads: handling_ms per
// step (base + spread * (step % 7)), its median as the summary, a recall.
void write_run(const fs::path& dir, const std::string& method, const std::string& budget, std::uint64_t seed,
               double base_ms, double recall, const std::string& status = "ok") {
  fs::create_directories(dir);
  const int steps = 40;
  std::vector<double> ms;
  std::ofstream csv(dir / "steps.csv");
  csv << "step,time_s,handling_ms\n";
  for (int s = 1; s <= steps; ++s) {
    ms.push_back(base_ms + 0.01 * static_cast<double>((s * 3 + static_cast<int>(seed)) % 7));
    csv << s << "," << 0.001 * s << "," << ms.back() << "\n";
  }
  std::sort(ms.begin(), ms.end());
  const nlohmann::json run = {
      {"schema", "tcbench.run/2"}, {"scene", "plates20"}, {"method", method}, {"method_label", method},
      {"settings", nlohmann::json::object()}, {"budget", {{"kind", "work"}, {"label", budget}}},
      {"steps", steps}, {"steps_requested", steps}, {"response", "implicit"}, {"seed", seed},
      {"overrides", nlohmann::json::array()}, {"status", status},
      {"summary", {{"handling_ms", {{"p50", 0.5 * (ms[19] + ms[20])}}}, {"recall_mean", recall}, {"tunneling", 0}}}};
  std::ofstream(dir / "run.json") << run.dump(2);
}

// Five seeds of interruptible and of full, as a sweep's runs/ folder.
fs::path results(const std::string& name, double interruptible_ms, double recall) {
  const fs::path dir = fresh_dir(name);
  for (std::uint64_t seed = 0; seed < 5; ++seed) {
    write_run(dir / "runs" / (std::string("i-s").append(std::to_string(seed))), "interruptible", "full-work/3", seed,
              interruptible_ms + 0.002 * static_cast<double>(seed), recall - 0.001 * static_cast<double>(seed));
    write_run(dir / "runs" / (std::string("f-s").append(std::to_string(seed))), "full", "none", seed, 3.0, 1.0);
  }
  return dir;
}

const MetricComparison& metric(const ComparedPair& p, const std::string& name) {
  for (const MetricComparison& m : p.metrics)
    if (m.metric == name) return m;
  FAIL("no metric " << name);
  return p.metrics.front();
}

int exit_status_of(const std::string& args) {
  const int raw = std::system((std::string(TCBENCH_EXE) + " compare " + args + " > /dev/null 2>&1").c_str());
  return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
}

}  // namespace

TEST_CASE("compare: two copies of one folder differ in nothing and pass", "[compare]") {
  const fs::path a = results("same_a", 1.0, 0.95), b = results("same_b", 1.0, 0.95);
  const std::vector<CompareThreshold> limits = {parse_compare_threshold("handling_ms.p50=+10%"),
                                                parse_compare_threshold("recall_mean=-0.01")};
  const Comparison c = compare_runs(collect_runs(a), collect_runs(b), {}, limits);
  REQUIRE(c.pairs.size() == 2);
  CHECK(c.only_a.empty());
  CHECK(c.only_b.empty());
  for (const ComparedPair& p : c.pairs) {
    CHECK(p.a_runs == 5);
    CHECK(p.a_label == p.b_label);
    for (const MetricComparison& m : p.metrics) {
      INFO(m.metric);
      CHECK(m.difference.median == 0.0);
      REQUIRE(m.difference.ci95);
      CHECK(m.difference.ci95->lo <= 0.0);
      CHECK(m.difference.ci95->hi >= 0.0);
    }
    CHECK(metric(p, "handling_ms.p50").u_over == "runs");
    CHECK(metric(p, "handling_ms.p50").u_test->p_two_sided > 0.5);
    for (const ThresholdVerdict& v : p.verdicts) CHECK(v.status == "pass");
  }
  CHECK_FALSE(c.regression());
  CHECK(exit_status_of(a.string() + " " + b.string() + " --threshold handling_ms.p50=+10%") == 0);
  fs::remove_all(a);
  fs::remove_all(b);
}

TEST_CASE("compare: a slower, less accurate candidate breaks its thresholds", "[compare]") {
  const fs::path a = results("reg_a", 1.0, 0.95), b = results("reg_b", 1.3, 0.90);
  const std::vector<CompareThreshold> limits = {parse_compare_threshold("handling_ms.p50=+10%"),
                                                parse_compare_threshold("recall_mean=-0.01")};
  const Comparison c = compare_runs(collect_runs(a), collect_runs(b), {}, limits);
  REQUIRE(c.pairs.size() == 2);
  const ComparedPair& interruptible = c.pairs[0].a_label.find("interruptible") != std::string::npos ? c.pairs[0] : c.pairs[1];
  const MetricComparison& time = metric(interruptible, "handling_ms.p50");
  CHECK(time.difference.median == Approx(0.3));
  CHECK(*time.relative == Approx(0.3 / time.a.median));
  CHECK(time.u_test->p_two_sided < 0.05);  // 5 against 5, all apart: p = 0.012
  CHECK(metric(interruptible, "recall_mean").difference.median == Approx(-0.05));
  REQUIRE(interruptible.verdicts.size() == 2);
  for (const ThresholdVerdict& v : interruptible.verdicts) CHECK(v.status == "fail");
  CHECK(c.regression());
  CHECK(exit_status_of(a.string() + " " + b.string() + " --threshold recall_mean=-0.01") == 1);
  CHECK(exit_status_of(a.string() + " " + b.string() + " --json") == 0);  // no threshold: a report, not a check
  fs::remove_all(a);
  fs::remove_all(b);
}

TEST_CASE("compare: a time beyond its limit but not significant does not fail; single runs use their steps",
          "[compare]") {
  const fs::path a = fresh_dir("single_a"), b = fresh_dir("single_b");
  write_run(a, "full", "none", 0, 1.0, 1.0);
  write_run(b, "interruptible", "full-work/3", 0, 1.0, 0.9);
  // Summary says 20 % slower, the steps say nothing changed: a noisy summary, not a regression.
  nlohmann::json record = nlohmann::json::parse(std::ifstream(b / "run.json"));
  record["summary"]["handling_ms"]["p50"] = 1.2 * record["summary"]["handling_ms"]["p50"].get<double>();
  std::ofstream(b / "run.json") << record.dump();
  const std::vector<CompareThreshold> limits = {parse_compare_threshold("handling_ms.p50=10%")};
  const Comparison c = compare_runs(collect_runs(a), collect_runs(b), {}, limits);
  REQUIRE(c.pairs.size() == 1);  // one configuration a side: compared whatever they are
  CHECK(c.pairs[0].a_label != c.pairs[0].b_label);
  const MetricComparison& time = metric(c.pairs[0], "handling_ms.p50");
  CHECK(time.u_over == "steps");
  CHECK(time.u_test->n_a == 40);
  CHECK_FALSE(time.difference.ci95);  // one run a side: no interval
  CHECK(c.pairs[0].verdicts[0].status == "pass");
  CHECK_THAT(c.pairs[0].verdicts[0].why, Catch::Matchers::Contains("not significant"));
  fs::remove_all(a);
  fs::remove_all(b);
}

TEST_CASE("compare: unpaired configurations, unknown metrics and bad input", "[compare]") {
  const fs::path a = results("unp_a", 1.0, 0.95), b = fresh_dir("unp_b");
  for (std::uint64_t seed = 0; seed < 2; ++seed) {
    write_run(b / (std::string("f").append(std::to_string(seed))), "full", "none", seed, 3.0, 1.0);
    write_run(b / (std::string("e").append(std::to_string(seed))), "every_nth", "none", seed, 1.0, 0.5);
  }
  const std::vector<CompareThreshold> limits = {parse_compare_threshold("recal_mean=-0.01")};
  const Comparison c = compare_runs(collect_runs(a), collect_runs(b), {}, limits);
  REQUIRE(c.pairs.size() == 1);
  CHECK(c.only_a.size() == 1);
  CHECK(c.only_b.size() == 1);
  REQUIRE(c.unknown.size() == 1);
  CHECK(c.unknown[0].status == "unknown metric");
  CHECK(c.regression());
  CHECK(format_comparison(c, "a", "b").find("only in B: plates20 every_nth none") != std::string::npos);
  CHECK(exit_status_of(a.string() + " " + b.string() + " --threshold recal_mean=-0.01") == 1);
  CHECK(exit_status_of(a.string() + " /nonexistent/results") == 2);
  CHECK(exit_status_of(a.string() + " " + b.string() + " --threshold recall_mean") == 2);
  for (const char* bad : {"recall_mean", "=1", "recall_mean=", "recall_mean=fast", "recall_mean=+-1", "x=-nan", "x=1%%"})
    CHECK_THROWS_AS(parse_compare_threshold(bad), InputError);
  const CompareThreshold rise = parse_compare_threshold("handling_ms.p99=+5%");
  CHECK(rise.direction == CompareThreshold::Direction::Rise);
  CHECK(rise.relative);
  CHECK(rise.limit == 5.0);
  const CompareThreshold either = parse_compare_threshold("jitter=0.002");
  CHECK(either.direction == CompareThreshold::Direction::Either);
  CHECK_FALSE(either.relative);
  fs::remove_all(a);
  fs::remove_all(b);
}
