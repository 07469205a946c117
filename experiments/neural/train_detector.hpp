#pragma once
/// `tcbench neural train`: one network for one latent family, trained with
/// exact labels (finger_labeller.hpp) by active or supervised learning
/// (method/neural/active_learning.hpp), saved for the `neural` method (a
/// scene's latent_model). The file is the network's tcbench-mlp-1 JSON
/// (mlp.hpp) plus a "trained" object saying how it was made: preset,
/// strategy, seed, labels, gradient steps, label and training seconds, build,
/// machine and time. Written atomically. Deterministic: the same settings
/// give the same parameters, bit for bit, on one build.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "method/neural/active_learning.hpp"

namespace tcb {

struct TrainDetectorSettings {
  std::string preset = "finger_small";
  neural::Strategy strategy = neural::Strategy::Active;
  std::uint64_t seed = 1;
  neural::LearningSettings learning;  ///< layers[0] is set from the latent size
  std::filesystem::path out;
  std::vector<std::string> command_line;
  std::function<void(const std::string&)> progress;  ///< after the bootstrap and each round (may be empty)
};

/// The experiment's learning defaults (neural_experiment_defaults(false)).
TrainDetectorSettings train_detector_defaults();

struct TrainedDetector {
  neural::Mlp<double> net;
  int labels = 0, gradient_steps = 0;
  double label_seconds = 0.0, train_seconds = 0.0;
};

/// Trains and writes settings.out. std::invalid_argument for an unknown preset.
TrainedDetector train_detector(const TrainDetectorSettings& settings);

}  // namespace tcb
