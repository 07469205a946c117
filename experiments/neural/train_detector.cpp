#include "experiments/neural/train_detector.hpp"

#include <fmt/format.h>

#include <chrono>

#include "experiments/neural/finger_labeller.hpp"
#include "experiments/neural/neural_experiment.hpp"
#include "experiments/run/provenance.hpp"
#include "sim/io/atomic_file.hpp"
#include "sim/latent/skinned_finger.hpp"

namespace tcb {

TrainDetectorSettings train_detector_defaults() {
  TrainDetectorSettings s;
  s.learning = neural_experiment_defaults(false).learning;
  return s;
}

TrainedDetector train_detector(const TrainDetectorSettings& settings) {
  const SkinnedFinger finger(finger_preset(settings.preset));
  FingerLabeller labeller(finger);
  neural::LearningSettings learning = settings.learning;
  learning.layers.front() = finger.latent_size();
  const auto start = std::chrono::steady_clock::now();
  int labels_spent = 0, steps_taken = 0;
  TrainedDetector out{neural::learn(settings.strategy, std::ref(labeller), learning, settings.seed,
                                    [&](const neural::Mlp<double>&, int labels, int steps) {
                                      labels_spent = labels;
                                      steps_taken = steps;
                                      if (settings.progress)
                                        settings.progress(fmt::format("{} labels, {} gradient steps", labels, steps));
                                    })};
  out.labels = labels_spent;
  out.gradient_steps = steps_taken;
  out.label_seconds = labeller.seconds();
  out.train_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() - out.label_seconds;
  nlohmann::ordered_json j = out.net.to_json();
  j["trained"] = {{"preset", settings.preset},
                  {"strategy", neural::strategy_name(settings.strategy)},
                  {"seed", settings.seed},
                  {"labels", out.labels},
                  {"gradient_steps", out.gradient_steps},
                  {"label_seconds", out.label_seconds},
                  {"train_seconds", out.train_seconds},
                  {"command_line", settings.command_line},
                  {"build", build_info()},
                  {"machine", machine_info()},
                  {"written", utc_timestamp()}};
  write_file_atomically(settings.out, j.dump() + "\n");
  return out;
}

}  // namespace tcb
