// The Eigen MLP, its losses and Adam (method/neural/): every gradient against
// central differences in double, reproducibility, save/load, and a training
// run that only succeeds if backpropagation is right.
#include "method/neural/mlp.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "method/neural/adam.hpp"
#include "method/neural/losses.hpp"
#include "sim/random/counter_random.hpp"

using namespace tcb;
using namespace tcb::neural;
using Vec = Eigen::VectorXd;
using Mat = Eigen::MatrixXd;

namespace {

Vec random_vec(Eigen::Index n, std::uint64_t seed, double scale = 1.0) {
  Vec v(n);
  for (Eigen::Index i = 0; i < n; ++i) v[i] = scale * uniform_pm1(seed, 77, static_cast<std::uint64_t>(i));
  return v;
}

double relative_error(const Vec& a, const Vec& b) { return (a - b).norm() / std::max(1e-12, b.norm()); }

// Central differences of f at x.
template <class F>
Vec numeric_gradient(F&& f, Vec x, double h = 1e-6) {
  Vec g(x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    const double xi = x[i];
    x[i] = xi + h;
    const double up = f(x);
    x[i] = xi - h;
    const double down = f(x);
    x[i] = xi;
    g[i] = (up - down) / (2.0 * h);
  }
  return g;
}

}  // namespace

TEST_CASE("mlp: the input gradient matches central differences", "[neural]") {
  for (const Activation act : {Activation::Tanh, Activation::Celu}) {
    const Mlp<double> net({5, 16, 16, 1}, act, 3);
    for (std::uint64_t k = 0; k < 4; ++k) {
      const Vec z = random_vec(5, 10 + k);
      Vec grad;
      const double r = net.value_and_input_gradient(z, grad);
      CHECK(r == net.forward(z)[0]);
      const Vec numeric = numeric_gradient([&](const Vec& x) { return net.forward(x)[0]; }, z);
      INFO(activation_name(act) << " sample " << k);
      CHECK(relative_error(grad, numeric) < 1e-6);
    }
  }
}

TEST_CASE("mlp: the parameter gradient matches central differences", "[neural]") {
  for (const Activation act : {Activation::Tanh, Activation::Celu}) {
    Mlp<double> net({3, 7, 5, 2}, act, 4);
    Mat z(3, 6);
    for (int c = 0; c < 6; ++c) z.col(c) = random_vec(3, 20 + static_cast<std::uint64_t>(c), 1.5);
    Mat weights(2, 6);  // L = sum(weights .* output): dL/dout = weights
    for (int c = 0; c < 6; ++c) weights.col(c) = random_vec(2, 40 + static_cast<std::uint64_t>(c));
    const Vec analytic = net.parameter_gradient(z, weights);
    const Vec theta = net.parameters();
    const Vec numeric = numeric_gradient(
        [&](const Vec& p) {
          Mlp<double> probe = net;
          probe.set_parameters(p);
          return probe.forward_batch(z).cwiseProduct(weights).sum();
        },
        theta);
    INFO(activation_name(act));
    CHECK(relative_error(analytic, numeric) < 1e-6);
    CHECK(static_cast<std::size_t>(theta.size()) == net.parameter_count());
    CHECK(net.parameter_count() == 3u * 7 + 7 + 7 * 5 + 5 + 5 * 2 + 2);
  }
}

TEST_CASE("losses: each gradient matches central differences", "[neural]") {
  const Vec r = random_vec(9, 5, 2.0);
  Vec label(9), depth(9);
  for (int i = 0; i < 9; ++i) label[i] = i % 3 == 0 ? 0.0 : 1.0, depth[i] = label[i] * (0.01 * i);
  depth[4] = depth[5];  // a tie: no pair between them
  Vec g;
  const auto check = [&](auto&& loss) {
    Vec analytic;
    loss(r, analytic);
    const Vec numeric = numeric_gradient([&](const Vec& x) { return loss(x, g); }, r);
    CHECK(relative_error(analytic, numeric) < 1e-6);
  };
  check([&](const Vec& x, Vec& d) { return cross_entropy(x, label, d); });
  check([&](const Vec& x, Vec& d) { return depth_regression(x, depth, 0.02, d); });
  check([&](const Vec& x, Vec& d) { return ranking(x, depth, 3.0, d); });  // margin wide enough that pairs are active
  check([&](const Vec& x, Vec& d) { return boundary(x, d); });
  // Values: cross-entropy at r = 0 is log 2; extreme logits stay finite.
  Vec zero = Vec::Zero(2), lab(2);
  lab << 0.0, 1.0;
  CHECK(cross_entropy(zero, lab, g) == Approx(std::log(2.0)));
  Vec huge(2);
  huge << 800.0, -800.0;
  CHECK(cross_entropy(huge, lab, g) == Approx(800.0));
  CHECK(std::isfinite(g[0]));
  // Ranking with no ordered pair is 0; empty inputs are 0 with empty gradients.
  CHECK(ranking(r, Vec(Vec::Zero(9)), 1.0, g) == 0.0);
  CHECK(boundary(Vec(), g) == 0.0);
  CHECK(g.size() == 0);
}

TEST_CASE("mlp: the same seed gives bit-identical weights, trained or not; another seed others", "[neural]") {
  const auto train = [](std::uint64_t seed) {
    Mlp<double> net({2, 8, 1}, Activation::Tanh, seed);
    Adam<double> adam(1e-2);
    Mat z(2, 16);
    Mat target(1, 16);
    for (int c = 0; c < 16; ++c) z.col(c) = random_vec(2, 100 + static_cast<std::uint64_t>(c)), target(0, c) = z(0, c) * z(1, c);
    Vec p = net.parameters();
    for (int step = 0; step < 50; ++step) {
      const Mat out = net.forward_batch(z);
      adam.step(p, net.parameter_gradient(z, 2.0 * (out - target) / 16.0));
      net.set_parameters(p);
    }
    return net;
  };
  CHECK(Mlp<double>({2, 8, 1}, Activation::Tanh, 9).parameters() == Mlp<double>({2, 8, 1}, Activation::Tanh, 9).parameters());
  CHECK(train(9).parameters() == train(9).parameters());
  CHECK(train(9).parameters() != train(10).parameters());
}

TEST_CASE("mlp: save and load reproduce the outputs exactly; a bad file names itself", "[neural]") {
  const auto dir = std::filesystem::temp_directory_path() / "tcbench_mlp_test";
  std::filesystem::create_directories(dir);
  const Mlp<double> net({4, 12, 12, 1}, Activation::Celu, 21);
  Mlp<double> perturbed = net;
  perturbed.set_parameters(net.parameters() * (1.0 / 3.0));  // digits that need all 17 to round-trip
  const std::string path = (dir / "net.json").string();
  perturbed.save(path);
  const Mlp<double> loaded = Mlp<double>::load(path);
  CHECK(loaded.parameters() == perturbed.parameters());
  CHECK(loaded.activation() == Activation::Celu);
  for (std::uint64_t k = 0; k < 5; ++k) CHECK(loaded.forward(random_vec(4, k))[0] == perturbed.forward(random_vec(4, k))[0]);
  const std::string bad = (dir / "bad.json").string();
  for (const char* text : {"{\"format\": \"tcbench-mlp-1\", \"activation\": \"relu\", \"layers\": [1, 1], \"parameters\": [0, 0]}",
                           "{\"format\": \"tcbench-mlp-1\", \"activation\": \"tanh\", \"layers\": [2, 1], \"parameters\": [0]}",
                           "not json", "{}"}) {
    std::ofstream(bad) << text;
    try {
      (void)Mlp<double>::load(bad);
      FAIL("loaded " << text);
    } catch (const std::runtime_error& e) {
      CHECK(std::string(e.what()).rfind(bad + ": ", 0) == 0);
    }
  }
  CHECK_THROWS_AS(Mlp<double>::load((dir / "missing.json").string()), std::runtime_error);
  std::filesystem::remove_all(dir);
}

TEST_CASE("adam: minimises a quadratic", "[neural]") {
  Vec p = Vec::Constant(3, 5.0);
  const Vec target = random_vec(3, 8);
  Adam<double> adam(0.05);
  for (int i = 0; i < 2000; ++i) adam.step(p, 2.0 * (p - target));
  CHECK((p - target).norm() < 1e-3);
  CHECK(adam.steps() == 2000);
}

TEST_CASE("mlp: cross-entropy training learns a disc (fails if backpropagation is wrong)", "[neural]") {
  Mlp<double> net({2, 16, 16, 1}, Activation::Tanh, 1);
  Adam<double> adam(1e-2);
  const int n = 256;
  Mat z(2, n);
  Vec label(n);
  for (int c = 0; c < n; ++c) {
    z.col(c) << uniform_pm1(2, 0, 2 * static_cast<std::uint64_t>(c)), uniform_pm1(2, 0, 2 * static_cast<std::uint64_t>(c) + 1);
    label[c] = z.col(c).norm() > 0.6 ? 1.0 : 0.0;
  }
  Vec p = net.parameters(), d;
  const double before = cross_entropy(Vec(net.forward_batch(z).row(0).transpose()), label, d);
  for (int step = 0; step < 1500; ++step) {
    const Vec r = net.forward_batch(z).row(0).transpose();
    cross_entropy(r, label, d);
    adam.step(p, net.parameter_gradient(z, d.transpose()));
    net.set_parameters(p);
  }
  const Vec r = net.forward_batch(z).row(0).transpose();
  int right = 0;
  for (int c = 0; c < n; ++c) right += (r[c] > 0.0) == (label[c] > 0.5);
  CHECK(cross_entropy(r, label, d) < 0.25 * before);
  CHECK(right > 0.95 * n);
}

TEST_CASE("mlp: a float network runs, and bad shapes are refused", "[neural]") {
  const Mlp<float> net({3, 4, 1}, Activation::Celu, 2);
  const Eigen::VectorXf out = net.forward(Eigen::VectorXf::Ones(3));
  CHECK(std::isfinite(out[0]));
  CHECK_THROWS_AS(Mlp<double>({3}, Activation::Tanh, 1), std::invalid_argument);
  CHECK_THROWS_AS(Mlp<double>({3, 0, 1}, Activation::Tanh, 1), std::invalid_argument);
  const Mlp<double> two({3, 4, 2}, Activation::Tanh, 1);
  Vec g;
  CHECK_THROWS_AS(two.value_and_input_gradient(Vec::Zero(3), g), std::invalid_argument);
  CHECK_THROWS_AS(two.forward(Vec::Zero(2)), std::invalid_argument);
}
