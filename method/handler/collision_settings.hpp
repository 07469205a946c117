#pragma once
/// The scene's [collision] table resolved against a built world: the hash's
/// cell size ("auto" = average edge length of all bodies at their current
/// positions), table size, hash function, and the response parameters of
/// every body pair ([collision] defaults, overridden by [[collision.pair]]
/// entries that name bodies or the objects they were stacked from).

#include <string>
#include <vector>

#include "method/detection/tet_hash_detection.hpp"
#include "method/response/penalty_response.hpp"
#include "sim/world/scene.hpp"

namespace tcb {

struct CollisionSettings {
  DetectionSettings detection;
  double dt_s = 1.0e-3;  ///< the scene's step: bounds explicit damping and friction
  std::size_t body_count = 0;
  std::vector<ResponseParams> pair_response;  ///< body_count^2, symmetric
  /// Settings that are allowed but likely to misbehave, in words (e.g. a
  /// response stiffness above the explicit stability bound 4 m / dt^2 of the
  /// lightest vertex of a colliding pair). The run records them.
  std::vector<std::string> warnings;
  const ResponseParams& response(std::size_t a, std::size_t b) const { return pair_response[a * body_count + b]; }
};

/// Average length of all tet edges of all bodies (m).
double average_edge_length(const World& world);

/// Throws InputError when a pair names no body or the hash is unknown.
CollisionSettings resolve_collision_settings(const World& world, const SceneDesc& scene);

}  // namespace tcb
