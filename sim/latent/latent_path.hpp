#pragma once
/// A body driven along a latent path (seed 002's harness scene): its
/// positions at time t are scale * D(z(t)) + position, D the skinned finger's
/// decoder (skinned_finger.hpp) and z(t) read from a CSV file
///   time_s,z0,z1,...,z{n-1}
///   0.0,-1,0,-1,0,...
/// with n the family's latent size, strictly increasing finite times and
/// finite codes (sim/io/numeric_csv.hpp's rules). Between samples the code is
/// interpolated linearly; before the first and after the last it holds.
/// Units: seconds; z is dimensionless (its entries map [-1, 1] onto the
/// joints' angle ranges).

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "sim/latent/skinned_finger.hpp"

namespace tcb {

struct LatentPath {
  std::vector<double> time_s;
  std::vector<Eigen::VectorXd> code;
  Eigen::VectorXd at(double t_s) const;
};

/// Reads a latent path of codes with `latent_size` entries; InputError naming
/// the file and the line otherwise.
LatentPath read_latent_path_csv(const std::filesystem::path& path, int latent_size);

/// What a latent-driven body needs to move (World::step) and what a
/// whole-body detector needs to judge it (method/neural/neural_handler.hpp).
struct LatentDrive {
  std::string family;                  ///< the preset, e.g. "finger_small"
  std::shared_ptr<const SkinnedFinger> finger;
  LatentPath path;
  double scale = 1.0;
  Vec3 position_m = Vec3::Zero();
  /// The network trained for this family (the scene's latent_model, resolved
  /// against the scene's folder); empty when the scene names none.
  std::filesystem::path model_path;
  /// scale * D(z) + position.
  std::vector<Vec3> positions_m(const Eigen::VectorXd& z) const;
};

}  // namespace tcb
