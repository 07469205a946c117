#pragma once
/// The neural self-collision experiment (seed 002, N-Penetrate) on the
/// skinned finger: active against supervised learning with the same labels
/// and gradient steps, judged on a held-out set of exactly labelled codes,
/// then ALM resolution with each trained network, judged by the oracle.
///
/// Writes into `out`, each file atomically:
/// - learning.csv: one row per (preset, strategy, seed, round): labels spent,
///   gradient steps, accuracy, FNR, FPR, precision, recall on the test set;
/// - alm.csv: one row per (preset, strategy, seed, margin): colliding test
///   codes attempted, resolved by the oracle's verdict on the ALM's answer,
///   the distances moved (median and mean, latent units) and the reference
///   distance (oracle bisection towards the rest code, the same codes);
/// - neural.json: settings, build and machine, test-set composition, label
///   and training cost, detector evaluation time, wall time.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "method/neural/active_learning.hpp"
#include "method/neural/alm.hpp"

namespace tcb {

struct NeuralExperimentSettings {
  std::vector<std::string> presets;  ///< latent families (sim/latent/skinned_finger.hpp)
  std::vector<std::uint64_t> seeds{1, 2, 3};
  int test_codes = 2000;
  neural::LearningSettings learning;  ///< layers[0] is set from the latent size
  std::vector<double> alm_margins{0.0, 1.0, 2.0};  ///< logits: c(z) = r(z) + margin
  int alm_codes = 60;                               ///< colliding test codes resolved per network
  neural::AlmSettings alm;
  int reference_bisections = 20;
  int jobs = 1;  ///< worker threads (results do not depend on it; label and training seconds are summed over workers)
  std::filesystem::path out;
  std::vector<std::string> command_line;
  std::function<void(const std::string&)> progress;  ///< one line per phase (may be empty)
};

/// The defaults of `tcbench neural experiment`, or its reduced form (--quick).
NeuralExperimentSettings neural_experiment_defaults(bool quick);

void run_neural_experiment(const NeuralExperimentSettings& settings);

/// Whether `neural_json` is a finished experiment's neural.json with the
/// seeds, presets, test codes, learning rounds and ALM margins of `wanted`
/// (reproduce --resume keeps it then; a --quick experiment is redone by a
/// full reproduce). False for a missing or unreadable file.
bool neural_results_match(const std::filesystem::path& neural_json, const NeuralExperimentSettings& wanted);

}  // namespace tcb
