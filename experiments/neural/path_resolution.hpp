#pragma once
/// `tcbench neural alm`: the ALM (method/neural/alm.hpp) as a time-critical
/// loop would run it. For each code of a latent path (latent_path.hpp's CSV),
/// the network's logit and the oracle's exact verdict; where the network says
/// "colliding", the ALM minimises |z - z0|^2 subject to logit(z) + margin <= 0
/// under a work budget per step (one unit per network evaluation), resumed
/// step after step until it is done, and the oracle judges its answer. So the
/// table says how many steps of a given budget a resolution takes, and
/// whether it resolves.
///
/// Writes `out` (CSV, atomically), one row per path sample:
///   time_s, logit, network_collides, oracle_collides, oracle_pd_m,
///   alm_steps, alm_evaluations, alm_feasible, alm_converged, distance,
///   resolved
/// (the ALM columns empty where the network says collision-free; distance in
/// latent units; resolved: the oracle finds the ALM's code collision-free).

#include <cstdint>
#include <filesystem>
#include <string>

#include "method/neural/alm.hpp"

namespace tcb {

struct PathResolutionSettings {
  std::string preset = "finger_small";
  std::filesystem::path model, path, out;
  double margin = 0.0;                 ///< logits
  std::uint64_t work_per_step = 0;     ///< the ALM's budget per step; 0: unlimited (done in one step)
  std::int64_t max_steps = 100000;     ///< a resolution still running after this many steps is abandoned
  neural::AlmSettings alm;
};

struct PathResolution {
  std::int64_t frames = 0, network_colliding = 0, oracle_colliding = 0, true_positives = 0;
  std::int64_t resolved = 0, abandoned = 0;
  std::int64_t steps_max = 0;          ///< the longest resolution, in steps of work_per_step
  double distance_median = 0.0;        ///< over the attempted frames (NaN when none)
};

/// Runs the table; InputError for an unknown preset, a bad model or path file.
PathResolution resolve_path(const PathResolutionSettings& settings);

}  // namespace tcb
