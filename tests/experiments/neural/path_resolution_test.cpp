// tcbench neural alm and gen: the ALM resumed under a work budget per step
// gives the answers of an unlimited run, the oracle judges them, and the
// labelled codes are reproducible and exact.
#include "experiments/neural/path_resolution.hpp"

#include <catch2/catch.hpp>

#include <unistd.h>

#include <fstream>
#include <sstream>

#include "experiments/neural/code_labels.hpp"
#include "experiments/neural/finger_labeller.hpp"
#include "experiments/run/provenance.hpp"
#include "method/neural/active_learning.hpp"
#include "sim/io/atomic_file.hpp"
#include "sim/io/input_error.hpp"

using namespace tcb;
namespace fs = std::filesystem;

namespace {

std::vector<std::vector<std::string>> read_csv(const fs::path& path) {
  std::vector<std::vector<std::string>> rows;
  std::stringstream in(read_file(path));
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::stringstream l(line);
    for (std::string c; std::getline(l, c, ',');) cells.push_back(c);
    if (!line.empty() && line.back() == ',') cells.push_back("");
    rows.push_back(cells);
  }
  return rows;
}

}  // namespace

TEST_CASE("neural alm: resumed under a work budget per step, the same answers as unlimited", "[neural]") {
  const fs::path dir = fs::temp_directory_path() / ("tcbench_path_resolution_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  // Every 20th sample of the committed path: both verdicts occur.
  const fs::path scenes = source_tree_dir() / "experiments" / "scenes";
  std::stringstream full(read_file(scenes / "finger_curl_path.csv"));
  std::string line, shortened;
  for (int i = 0; std::getline(full, line); ++i)
    if (i == 0 || i % 20 == 1) shortened += line + "\n";
  write_file_atomically(dir / "path.csv", shortened);
  PathResolutionSettings s;
  s.model = scenes / "finger_small_active.json";
  s.path = dir / "path.csv";
  s.margin = 2.0;
  s.out = dir / "unlimited.csv";
  const PathResolution once = resolve_path(s);
  s.work_per_step = 3;
  s.out = dir / "budget.csv";
  const PathResolution stepped = resolve_path(s);
  INFO("frames " << once.frames << ", network colliding " << once.network_colliding << ", resolved " << once.resolved);
  CHECK(once.frames == 11);
  CHECK(once.network_colliding > 0);
  CHECK(once.network_colliding < once.frames);
  CHECK(once.steps_max == 1);
  CHECK(stepped.steps_max > 1);
  CHECK(stepped.resolved == once.resolved);
  const auto a = read_csv(dir / "unlimited.csv"), b = read_csv(dir / "budget.csv");
  REQUIRE(a.size() == 12);
  REQUIRE(b.size() == a.size());
  const SkinnedFinger finger(finger_preset("finger_small"));
  FingerLabeller labeller(finger);
  const LatentPath path = read_latent_path_csv(s.path, 12);
  for (std::size_t r = 1; r < a.size(); ++r) {
    INFO("row " << r);
    REQUIRE(a[r].size() == 11);
    for (std::size_t c = 0; c < 11; ++c)
      if (c != 5) CHECK(a[r][c] == b[r][c]);  // all but alm_steps
    CHECK(a[r][3] == (labeller.penetration(path.code[r - 1]).penetrates ? "1" : "0"));
    if (a[r][2] == "1") {
      // evaluations / 3 steps, rounded up (the last step may use fewer), plus
      // at most one more: a budget spent by the evaluation after which the
      // solver's stop test passes leaves that test to the next step.
      const long evaluations = std::stol(b[r][6]), steps = std::stol(b[r][5]);
      CHECK(steps >= (evaluations + 2) / 3);
      CHECK(steps <= (evaluations + 2) / 3 + 1);
    } else {
      CHECK(a[r][5].empty());
    }
  }
  fs::remove_all(dir);
}

TEST_CASE("neural gen: the same seed gives the same codes, each with its exact label", "[neural]") {
  const fs::path dir = fs::temp_directory_path() / ("tcbench_code_labels_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const CodeLabelCounts c = label_uniform_codes("finger_small", 40, 5, dir / "a.csv");
  label_uniform_codes("finger_small", 40, 5, dir / "b.csv");
  label_uniform_codes("finger_small", 40, 6, dir / "c.csv");
  CHECK(read_file(dir / "a.csv") == read_file(dir / "b.csv"));
  CHECK(read_file(dir / "a.csv") != read_file(dir / "c.csv"));
  CHECK(c.codes == 40);
  CHECK(c.colliding > 0);
  CHECK(c.colliding < 40);
  const auto rows = read_csv(dir / "a.csv");
  REQUIRE(rows.size() == 41);
  CHECK(rows[0].back() == "pd_m");
  const SkinnedFinger finger(finger_preset("finger_small"));
  FingerLabeller labeller(finger);
  for (std::size_t r = 1; r < rows.size(); r += 7) {
    const Eigen::VectorXd z = neural::uniform_code(12, 5, 7, r - 1);
    CHECK(std::stod(rows[r][0]) == z[0]);  // printed to round-trip
    const SelfPenetration p = labeller.penetration(z);
    CHECK(rows[r][12] == (p.penetrates ? "1" : "0"));
    CHECK(std::stod(rows[r][13]) == p.pd_m);
  }
  CHECK_THROWS_AS(label_uniform_codes("finger_huge", 1, 1, dir / "d.csv"), InputError);
  fs::remove_all(dir);
}
