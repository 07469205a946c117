#pragma once
/// Collision handling's configuration: the scene's [collision] table as
/// plain data (CollisionDesc), and the same resolved once per run against the
/// built world (CollisionSettings), which every handler's init() receives:
/// the hash's cell size ("auto" = average edge length of all bodies at their
/// current positions), table size, hash function, and the response parameters
/// of every body pair ([collision] defaults, overridden by [[collision.pair]]
/// entries that name bodies or the objects they were stacked from).

#include <optional>
#include <string>
#include <vector>

#include "method/detection/tet_hash_detection.hpp"
#include "method/response/penalty_response.hpp"
#include "sim/world/world.hpp"

namespace tcb {

/// Response parameters for one pair of objects ([[collision.pair]]); a name
/// matches a body or the object a stack was made from.
struct CollisionPairDesc {
  std::string a, b;
  std::optional<double> stiffness_n_per_m, damping_n_s_per_m, friction;
  int source_line = 0;
};

/// The [collision] table as plain data.
struct CollisionDesc {
  std::optional<double> cell_size_m;  ///< nullopt = "auto" (average edge length)
  double cell_size_auto_factor = 1.0; ///< "auto*K": K times the average edge length
  HashFunction hash = HashFunction::Mixed;  ///< "mixed", or "paper" (Teschner et al. 2003)
  std::size_t table_size = 0;         ///< 0 = automatic (the next prime above 2 K tets + 1)
  double table_size_auto_factor = 1.0;  ///< K of the automatic table size ("auto*K")
  double response_stiffness_n_per_m = 1.0e4;
  double damping_n_s_per_m = 0.0;
  double friction = 0.3;
  /// How penalty forces are integrated (penalty_response.hpp): implicitly with
  /// the bodies (default) or as explicit external forces (the method before).
  ResponseMode response_mode = ResponseMode::Implicit;
  std::vector<CollisionPairDesc> pairs;
  /// Threads for the cycle's tet and surface hashing, point queries, border
  /// depths and forces (collision_cycle.hpp); 1 = none started. The results
  /// are the same for every count.
  int threads = 1;
};

struct CollisionSettings {
  DetectionSettings detection;  ///< cell and table sizes resolved (never 0)
  double mean_edge_m = 0.0;     ///< the average edge length "auto" refers to
  std::size_t tets = 0;         ///< of all bodies: the table's automatic size counts them
  double dt_s = 1.0e-3;  ///< the scene's step: bounds explicit damping and friction
  ResponseMode response_mode = ResponseMode::Implicit;
  int threads = 1;  ///< as CollisionDesc::threads
  std::size_t body_count = 0;
  std::vector<ResponseParams> pair_response;  ///< body_count^2, symmetric
  /// Settings that are allowed but likely to misbehave, in words (e.g. under
  /// explicit response, a response stiffness above the stability bound
  /// 4 m / dt^2 of the lightest vertex of a colliding pair). The run records them.
  std::vector<std::string> warnings;
  const ResponseParams& response(std::size_t a, std::size_t b) const { return pair_response[a * body_count + b]; }
};

/// Average length of all tet edges of all bodies (m).
double average_edge_length(const World& world);

/// Resolves `desc` for `world` stepped with dt_s. InputError naming `file` and
/// the pair's line when a [[collision.pair]] names no body, and naming `file`
/// when implicit response meets a body whose integrator has no linear step
/// (mass_spring with verlet).
CollisionSettings resolve_collision_settings(const World& world, const CollisionDesc& desc, double dt_s,
                                             const std::string& file = "scene");

}  // namespace tcb
