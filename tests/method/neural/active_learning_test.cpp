// Training the detector (method/neural/active_learning.hpp) on an analytic
// labeller: a code collides when it lies outside the circle of radius 0.7,
// with depth |z| - 0.7. No oracle here; the experiment hands that in.
#include "method/neural/active_learning.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace tcb;
using namespace tcb::neural;

namespace {

constexpr double kRadius = 0.7;

Label circle_label(const Eigen::VectorXd& z) {
  const double d = z.norm() - kRadius;
  return {d > 0.0, std::max(0.0, d)};
}

LearningSettings small_settings() {
  LearningSettings s;
  s.layers = {2, 16, 16, 1};
  s.bootstrap_labels = 60;
  s.bootstrap_steps = 300;
  s.rounds = 4;
  s.labels_per_round = 40;
  s.steps_per_round = 300;
  s.train.batch = 32;
  s.train.learning_rate = 1e-2;
  s.train.depth_scale_m = 0.1;
  s.train.boundary_depth_m = 0.02;
  return s;
}

double accuracy(const Mlp<double>& net) {
  int right = 0, total = 0;
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j) {
      Eigen::VectorXd z(2);
      z << -1.0 + (i + 0.5) / 20.0, -1.0 + (j + 0.5) / 20.0;
      right += (net.forward(z)[0] > 0.0) == circle_label(z).collides, ++total;
    }
  return static_cast<double>(right) / total;
}

}  // namespace

TEST_CASE("learning: both strategies learn the circle, with the labels and steps they are given", "[neural]") {
  for (const Strategy strategy : {Strategy::Supervised, Strategy::Active}) {
    const LearningSettings s = small_settings();
    std::vector<int> labels_seen, steps_seen;
    std::vector<Sample> labelled;
    const Mlp<double> net = learn(strategy, circle_label, s, 7,
                                  [&](const Mlp<double>&, int labels, int steps) {
                                    labels_seen.push_back(labels), steps_seen.push_back(steps);
                                  }, &labelled);
    CHECK(labels_seen == std::vector<int>{60, 100, 140, 180, 220});
    CHECK(steps_seen == std::vector<int>{300, 600, 900, 1200, 1500});
    CHECK(labelled.size() == 220u);
    CHECK(accuracy(net) > 0.93);
  }
}

TEST_CASE("learning: active samples sit nearer the true boundary than uniform ones", "[neural]") {
  const LearningSettings s = small_settings();
  std::vector<Sample> active, supervised;
  learn(Strategy::Active, circle_label, s, 3, {}, &active);
  learn(Strategy::Supervised, circle_label, s, 3, {}, &supervised);
  // The rounds' samples (after the shared bootstrap), minus the exploration share.
  const auto mean_gap = [&](const std::vector<Sample>& v, bool pulled_only) {
    double sum = 0.0;
    int n = 0;
    const int explore = static_cast<int>(std::lround(s.exploration_share * s.labels_per_round));
    for (std::size_t i = static_cast<std::size_t>(s.bootstrap_labels); i < v.size(); ++i) {
      const int k = static_cast<int>(i - static_cast<std::size_t>(s.bootstrap_labels)) % s.labels_per_round;
      if (pulled_only && k < explore) continue;
      sum += std::abs(v[i].z.norm() - kRadius), ++n;
    }
    return sum / n;
  };
  CHECK(mean_gap(active, true) < 0.5 * mean_gap(supervised, false));
  // The shared bootstrap is the same codes for both.
  for (int i = 0; i < s.bootstrap_labels; ++i) CHECK(active[static_cast<std::size_t>(i)].z == supervised[static_cast<std::size_t>(i)].z);
}

TEST_CASE("learning: the same seed gives bit-identical weights, another seed others", "[neural]") {
  const LearningSettings s = small_settings();
  for (const Strategy strategy : {Strategy::Supervised, Strategy::Active}) {
    const Mlp<double> a = learn(strategy, circle_label, s, 11, {});
    const Mlp<double> b = learn(strategy, circle_label, s, 11, {});
    const Mlp<double> c = learn(strategy, circle_label, s, 12, {});
    CHECK(a.parameters() == b.parameters());
    CHECK(a.parameters() != c.parameters());
  }
}

TEST_CASE("learning: pulling to the boundary reaches the network's 0.5 level set", "[neural]") {
  const Mlp<double> net = learn(Strategy::Supervised, circle_label, small_settings(), 5, {});
  int reached = 0;
  for (int i = 0; i < 50; ++i) {
    const Eigen::VectorXd z = pull_to_boundary(net, uniform_code(2, 99, 0, static_cast<std::uint64_t>(i)), 20, 0.5);
    CHECK(z.cwiseAbs().maxCoeff() <= 1.0);
    reached += std::abs(net.forward(z)[0]) < 1e-3;
  }
  CHECK(reached >= 45);  // a few may stop at the box's faces
}

TEST_CASE("learning: a network that does not end in one logit is refused", "[neural]") {
  LearningSettings s = small_settings();
  s.layers = {2, 8, 2};
  CHECK_THROWS_AS(learn(Strategy::Active, circle_label, s, 1, {}), std::invalid_argument);
}
