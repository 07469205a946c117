#pragma once
/// A prescribed path for a driven object (a haptic probe, a mouse-driven
/// tool): the object's position over time, read from a CSV file
///   time_s,x_m,y_m,z_m
///   0.000,0.0,0.36,0.06
///   ...
/// with strictly increasing, finite times and finite positions. The position
/// plays the role of the scene's `position` key (a translation applied after
/// scaling). Between samples it is interpolated linearly; before the first
/// and after the last sample it holds. Units: seconds and metres.

#include <filesystem>
#include <vector>

#include "sim/mesh/tet_mesh.hpp"

namespace tcb {

struct Trajectory {
  std::vector<double> time_s;
  std::vector<Vec3> position_m;
  Vec3 at(double t_s) const;
};

/// Reads a trajectory CSV; InputError naming the file and the line otherwise.
Trajectory read_trajectory_csv(const std::filesystem::path& path);

}  // namespace tcb
