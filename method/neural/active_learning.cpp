#include "method/neural/active_learning.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "method/neural/losses.hpp"
#include "sim/random/counter_random.hpp"

namespace tcb::neural {
namespace {

using Vec = Eigen::VectorXd;

// Streams of counter_random: each kind of draw its own, so adding draws of
// one kind never shifts another.
constexpr std::uint64_t kStreamBootstrap = 1, kStreamRound = 2, kStreamBatch = 3, kStreamInit = 4;

// The four terms on one batch: the loss, and dL/dr per sample.
double batch_loss(const Vec& r, const std::vector<const Sample*>& batch, const TrainSettings& s, Vec& dloss_dr) {
  const Eigen::Index n = r.size();
  dloss_dr = Vec::Zero(n);
  Vec label(n), depth(n);
  std::vector<Eigen::Index> positive, boundary_set;
  for (Eigen::Index i = 0; i < n; ++i) {
    const Label& l = batch[static_cast<std::size_t>(i)]->label;
    label[i] = l.collides ? 1.0 : 0.0;
    depth[i] = l.collides ? l.depth_m : 0.0;
    if (l.collides) (l.depth_m > s.boundary_depth_m ? positive : boundary_set).push_back(i);
  }
  Vec d;
  double loss = s.weight_ce * cross_entropy(r, label, d);
  dloss_dr += s.weight_ce * d;
  loss += s.weight_rank * ranking(r, depth, s.ranking_margin, d);
  dloss_dr += s.weight_rank * d;
  const auto subset_term = [&](const std::vector<Eigen::Index>& rows, double weight, auto&& term) {
    if (rows.empty() || weight == 0.0) return;
    Vec rs(static_cast<Eigen::Index>(rows.size())), ds(rs.size()), g;
    for (std::size_t k = 0; k < rows.size(); ++k) rs[static_cast<Eigen::Index>(k)] = r[rows[k]], ds[static_cast<Eigen::Index>(k)] = depth[rows[k]];
    loss += weight * term(rs, ds, g);
    for (std::size_t k = 0; k < rows.size(); ++k) dloss_dr[rows[k]] += weight * g[static_cast<Eigen::Index>(k)];
  };
  subset_term(positive, s.weight_depth, [&](const Vec& rs, const Vec& ds, Vec& g) { return depth_regression(rs, ds, s.depth_scale_m, g); });
  subset_term(boundary_set, s.weight_boundary, [&](const Vec& rs, const Vec&, Vec& g) { return boundary(rs, g); });
  return loss;
}

Eigen::MatrixXd codes_of(const std::vector<const Sample*>& batch) {
  Eigen::MatrixXd z(batch.front()->z.size(), static_cast<Eigen::Index>(batch.size()));
  for (std::size_t i = 0; i < batch.size(); ++i) z.col(static_cast<Eigen::Index>(i)) = batch[i]->z;
  return z;
}

}  // namespace

const char* strategy_name(Strategy strategy) { return strategy == Strategy::Active ? "active" : "supervised"; }

Vec uniform_code(int latent_size, std::uint64_t seed, std::uint64_t stream, std::uint64_t index) {
  Vec z(latent_size);
  for (int k = 0; k < latent_size; ++k)
    z[k] = uniform_pm1(seed, stream, index * static_cast<std::uint64_t>(latent_size) + static_cast<std::uint64_t>(k));
  return z;
}

Vec pull_to_boundary(const Mlp<double>& net, Vec z, int iterations, double max_step) {
  Vec grad;
  for (int it = 0; it < iterations; ++it) {
    const double r = net.value_and_input_gradient(z, grad);
    const double g2 = grad.squaredNorm();
    if (std::abs(r) < 1e-3 || !(g2 > 0.0)) break;
    Vec step = -r / g2 * grad;  // Newton on the scalar r(z) = 0, along the gradient
    const double length = step.norm();
    if (length > max_step) step *= max_step / length;
    z = (z + step).cwiseMax(-1.0).cwiseMin(1.0);
  }
  return z;
}

void train_steps(Mlp<double>& net, Adam<double>& adam, const std::vector<Sample>& samples, const TrainSettings& s,
                 int steps, std::uint64_t seed, std::uint64_t& draw) {
  if (samples.empty() || steps <= 0) return;
  const std::size_t batch_size = std::min<std::size_t>(static_cast<std::size_t>(std::max(1, s.batch)), samples.size());
  std::vector<const Sample*> batch(batch_size);
  Vec params = net.parameters();
  for (int step = 0; step < steps; ++step) {
    for (auto& b : batch) {
      const double u = uniform_01(seed, kStreamBatch, draw++);
      b = &samples[std::min(samples.size() - 1, static_cast<std::size_t>(u * static_cast<double>(samples.size())))];
    }
    const Eigen::MatrixXd z = codes_of(batch);
    const Vec grad = net.gradient_through(z, [&](const Eigen::MatrixXd& out) {
      Vec dloss_dr;
      batch_loss(out.row(0).transpose(), batch, s, dloss_dr);
      return Eigen::MatrixXd(dloss_dr.transpose());
    });
    adam.step(params, grad);
    net.set_parameters(params);
  }
}

double mean_loss(const Mlp<double>& net, const std::vector<Sample>& samples, const TrainSettings& s) {
  if (samples.empty()) return 0.0;
  std::vector<const Sample*> all;
  for (const Sample& x : samples) all.push_back(&x);
  const Vec r = net.forward_batch(codes_of(all)).row(0).transpose();
  Vec d;
  return batch_loss(r, all, s, d);
}

Mlp<double> learn(Strategy strategy, const Labeller& labeller, const LearningSettings& settings, std::uint64_t seed,
                  const RoundObserver& observe, std::vector<Sample>* labels_out) {
  if (settings.layers.size() < 2 || settings.layers.back() != 1)
    throw std::invalid_argument("learn: the network must map the code to one logit");
  const int n = settings.layers.front();
  Mlp<double> net(settings.layers, settings.activation, counter_bits(seed, kStreamInit, 0));
  Adam<double> adam(settings.train.learning_rate);
  std::vector<Sample> samples;
  std::uint64_t draw = 0;
  int steps = 0;
  // The bootstrap is the same uniform sample for both strategies (same seed):
  // the curves part only where the strategies differ.
  for (int i = 0; i < settings.bootstrap_labels; ++i) {
    Vec z = uniform_code(n, seed, kStreamBootstrap, static_cast<std::uint64_t>(i));
    samples.push_back({z, labeller(z)});
  }
  train_steps(net, adam, samples, settings.train, settings.bootstrap_steps, seed, draw);
  steps += settings.bootstrap_steps;
  if (observe) observe(net, static_cast<int>(samples.size()), steps);
  std::uint64_t index = 0;
  const int explore = static_cast<int>(std::lround(settings.exploration_share * settings.labels_per_round));
  for (int round = 0; round < settings.rounds; ++round) {
    for (int k = 0; k < settings.labels_per_round; ++k) {
      Vec z = uniform_code(n, seed, kStreamRound, index++);
      if (strategy == Strategy::Active && k >= explore)
        z = pull_to_boundary(net, z, settings.pull_iterations, settings.max_pull_step);
      samples.push_back({z, labeller(z)});
    }
    train_steps(net, adam, samples, settings.train, settings.steps_per_round, seed, draw);
    steps += settings.steps_per_round;
    if (observe) observe(net, static_cast<int>(samples.size()), steps);
  }
  if (labels_out) *labels_out = std::move(samples);
  return net;
}

}  // namespace tcb::neural
