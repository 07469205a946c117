#pragma once
/// Training the neural self-collision detector (seed 002, N-Penetrate §4):
/// supervised on uniform codes, or actively, with samples pulled to the
/// network's decision boundary. Both get the same labeller, the same number
/// of labels and the same number of gradient steps, so a learning curve
/// compares where the labels were spent and nothing else.
///
/// The detector is an MLP from a latent code z to a logit r; it calls D(z)
/// self-colliding when sigmoid(r) > 0.5 (r > 0). Labels carry the exact
/// verdict and a depth (metres, 0 when collision-free). Samples split into
/// the paper's three sets: positive (depth > boundary_depth_m), boundary
/// (colliding, depth <= boundary_depth_m), negative (collision-free). Each
/// minibatch's loss is
///     w_ce CE(all) + w_depth (r - depth/depth_scale)^2 (positive)
///   + w_rank ranking(all, by depth) + w_boundary r^2 (boundary),
/// the four terms of the seed (losses.hpp).
///
/// Active learning (the paper's risk-seeking sampler): after a uniform
/// bootstrap, each round draws uniform codes and pulls each to the current
/// 0.5 level set by Newton steps on r(z) = 0 (a few steps, each at most
/// max_pull_step long, kept inside [-1, 1]^n); a share of every round stays
/// uniform (exploration). The new codes are labelled and the network is
/// fine-tuned on everything labelled so far.
///
/// Reproducible: every random draw comes from counter_random (seed, stream,
/// index), so the same seed gives bit-identical weights for one build (across
/// machines as far as their tanh and exp agree, mlp.hpp). The labeller is
/// handed in: this file never sees the oracle.

#include <cstdint>
#include <functional>
#include <vector>

#include <Eigen/Dense>

#include "method/neural/adam.hpp"
#include "method/neural/mlp.hpp"

namespace tcb::neural {

struct Label {
  bool collides = false;
  double depth_m = 0.0;
};

/// The exact verdict for a code (the experiment hands in the oracle).
using Labeller = std::function<Label(const Eigen::VectorXd& z)>;

struct Sample {
  Eigen::VectorXd z;
  Label label;
};

enum class Strategy { Supervised, Active };
const char* strategy_name(Strategy strategy);

struct TrainSettings {
  int batch = 128;
  double learning_rate = 1e-3;
  double depth_scale_m = 0.01;     ///< the depth that maps to logit 1
  double boundary_depth_m = 1e-3;  ///< colliding with depth <= this: the boundary set
  double ranking_margin = 0.1;     ///< logits
  double weight_ce = 1.0, weight_depth = 0.1, weight_rank = 0.1, weight_boundary = 0.5;
};

struct LearningSettings {
  std::vector<int> layers;  ///< input size first, 1 last
  Activation activation = Activation::Tanh;
  int bootstrap_labels = 200;
  int bootstrap_steps = 1000;
  int rounds = 8;
  int labels_per_round = 100;
  int steps_per_round = 500;
  double exploration_share = 0.25;  ///< of each active round's labels, drawn uniformly
  int pull_iterations = 8;
  double max_pull_step = 0.5;
  TrainSettings train;
};

/// Called after the bootstrap and after every round with the network, the
/// labels spent so far and the gradient steps taken so far.
using RoundObserver = std::function<void(const Mlp<double>& net, int labels, int gradient_steps)>;

/// A uniform code in [-1, 1]^n: draw `index` of `stream` under `seed`.
Eigen::VectorXd uniform_code(int latent_size, std::uint64_t seed, std::uint64_t stream, std::uint64_t index);

/// Newton steps towards r(z) = 0 from z (see above). Returns the pulled code.
Eigen::VectorXd pull_to_boundary(const Mlp<double>& net, Eigen::VectorXd z, int iterations, double max_step);

/// `steps` Adam steps on minibatches drawn (with replacement) from `samples`;
/// `draw` numbers the minibatch draws of a whole learning run.
void train_steps(Mlp<double>& net, Adam<double>& adam, const std::vector<Sample>& samples,
                 const TrainSettings& settings, int steps, std::uint64_t seed, std::uint64_t& draw);

/// The mean of the four loss terms over `samples` (for tests and logs).
double mean_loss(const Mlp<double>& net, const std::vector<Sample>& samples, const TrainSettings& settings);

/// A whole learning run; returns the trained network. `labels_out`, when not
/// null, receives every labelled sample in the order they were labelled.
Mlp<double> learn(Strategy strategy, const Labeller& labeller, const LearningSettings& settings, std::uint64_t seed,
                  const RoundObserver& observe, std::vector<Sample>* labels_out = nullptr);

}  // namespace tcb::neural
