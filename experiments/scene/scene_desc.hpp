#pragma once
/// A scene file as plain data (CONTRACT: docs/contract.md "Scene files"): the
/// world to simulate (sim/), how collisions are handled (method/), the
/// methods' own settings, and what the run itself needs (length, stability
/// bound, which scene metrics apply). Read by scene_file.hpp.

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>

#include "method/handler/collision_settings.hpp"
#include "method/handler/method_settings.hpp"
#include "sim/world/perturbation.hpp"
#include "sim/world/world_desc.hpp"

namespace tcb {

struct SceneDesc {
  std::string name;
  std::filesystem::path path;  ///< the scene file (empty when built in code)
  std::int64_t steps = 1000;
  WorldDesc world;
  CollisionDesc collision;
  /// [method.NAME] tables, checked against each method's schema; a method
  /// without a table runs with its defaults.
  std::map<std::string, MethodSettings> methods;
  /// A vertex faster than this marks the run unstable (an explosion).
  double max_speed_m_per_s = 1.0e3;
  /// A run whose energy rises by more than this share of what it started with
  /// and was given is unstable (experiments/metrics/energy_meter.hpp).
  double max_energy_gain = 0.5;
  /// [metrics] jitter: the scene's jitter measure ("vertical_velocity_rms"), empty for none.
  std::string jitter_measure;
  /// [perturb]: initial conditions drawn from the run's seed (sim/world/perturbation.hpp).
  Perturbation perturb;
};

}  // namespace tcb
