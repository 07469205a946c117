// The neural experiment end to end at a toy size: the files it writes, and
// the exact labels it trains on (experiments/neural/).
#include "experiments/neural/neural_experiment.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "experiments/neural/detector_scores.hpp"
#include "experiments/neural/finger_labeller.hpp"

using namespace tcb;
namespace fs = std::filesystem;

namespace {

std::vector<std::string> lines_of(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

}  // namespace

TEST_CASE("neural experiment: a toy run writes the learning curve, the ALM table and neural.json", "[neural]") {
  const fs::path out = fs::temp_directory_path() / ("tcbench_neural_experiment_test_" + std::to_string(::getpid()));
  fs::remove_all(out);
  NeuralExperimentSettings s = neural_experiment_defaults(true);
  s.seeds = {1};
  s.test_codes = 40;
  s.learning.layers = {0, 8, 1};
  s.learning.bootstrap_labels = 16;
  s.learning.bootstrap_steps = 10;
  s.learning.rounds = 2;
  s.learning.labels_per_round = 8;
  s.learning.steps_per_round = 10;
  s.alm_codes = 3;
  s.alm_margins = {0.0, 1.0};
  s.reference_bisections = 4;
  s.out = out;
  run_neural_experiment(s);
  const auto learning = lines_of(out / "learning.csv");
  REQUIRE(learning.size() == 1 + 2 * 3);  // header; 2 strategies x (bootstrap + 2 rounds)
  CHECK(learning[0] == "preset,strategy,seed,labels,gradient_steps,test_codes,accuracy,fnr,fpr,precision,recall");
  CHECK(learning[1].rfind("finger_small,supervised,1,16,10,40,", 0) == 0);
  CHECK(learning[6].rfind("finger_small,active,1,32,30,40,", 0) == 0);
  const auto alm = lines_of(out / "alm.csv");
  REQUIRE(alm.size() == 1 + 2 * 2);  // 2 networks x 2 margins
  CHECK(alm[1].rfind("finger_small,supervised,1,0,3,", 0) == 0);
  std::ifstream meta_in(out / "neural.json");
  const auto meta = nlohmann::json::parse(meta_in);
  CHECK(meta["presets"][0]["vertices"] == 464);
  CHECK(meta["presets"][0]["test_codes"] == 40);
  CHECK(meta["presets"][0]["label_ms_per_code"].get<double>() > 0.0);
  CHECK(meta["build"].contains("git_sha"));
  CHECK(meta["machine"].contains("cpu"));
  // Three workers write the same files (the jobs write into their own slots).
  const fs::path threaded = out.string() + "_jobs3";
  fs::remove_all(threaded);
  s.out = threaded;
  s.jobs = 3;
  run_neural_experiment(s);
  CHECK(lines_of(threaded / "learning.csv") == learning);
  CHECK(lines_of(threaded / "alm.csv") == alm);
  // reproduce --resume keeps results only of the same seeds and presets.
  CHECK(neural_results_match(out / "neural.json", s));
  NeuralExperimentSettings other = s;
  other.seeds = {1, 2};
  CHECK_FALSE(neural_results_match(out / "neural.json", other));
  other = s;
  other.presets = {"finger_small", "finger_large"};
  CHECK_FALSE(neural_results_match(out / "neural.json", other));
  other = s;
  other.learning.rounds = 3;
  CHECK_FALSE(neural_results_match(out / "neural.json", other));
  other = s;
  other.test_codes = 41;
  CHECK_FALSE(neural_results_match(out / "neural.json", other));
  CHECK_FALSE(neural_results_match(out / "missing.json", s));
  fs::remove_all(out);
  fs::remove_all(threaded);
}

TEST_CASE("neural experiment: labels are the oracle's, and scores count them", "[neural]") {
  const SkinnedFinger finger(finger_preset("finger_small"));
  FingerLabeller labeller(finger);
  CHECK_FALSE(labeller(finger.rest_code()).collides);
  const neural::Label curl = labeller(finger.full_curl_code());
  CHECK(curl.collides);
  CHECK(curl.depth_m > 0.0);
  CHECK(labeller.labels() == 2);
  // A network whose logit is the first code entry: colliding iff z0 > 0.
  neural::Mlp<double> net({12, 1}, neural::Activation::Tanh, 1);
  Eigen::VectorXd p = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(net.parameter_count()));
  p[0] = 1.0;
  net.set_parameters(p);
  std::vector<neural::Sample> test;
  Eigen::VectorXd pos = Eigen::VectorXd::Zero(12), neg = pos;
  pos[0] = 0.5, neg[0] = -0.5;
  test.push_back({pos, {true, 0.01}});   // true positive
  test.push_back({pos, {false, 0.0}});   // false positive
  test.push_back({neg, {true, 0.01}});   // false negative
  test.push_back({neg, {false, 0.0}});   // true negative
  test.push_back({neg, {false, 0.0}});   // true negative
  const DetectorScores scores = score_detector(net, test);
  CHECK(scores.true_positive == 1);
  CHECK(scores.false_positive == 1);
  CHECK(scores.false_negative == 1);
  CHECK(scores.true_negative == 2);
  CHECK(scores.accuracy() == Approx(0.6));
  CHECK(scores.false_negative_rate() == Approx(0.5));
  CHECK(scores.false_positive_rate() == Approx(1.0 / 3.0));
  CHECK(scores.precision() == Approx(0.5));
  CHECK(std::isnan(score_detector(net, {}).accuracy()));
}
