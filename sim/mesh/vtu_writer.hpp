#pragma once
/// ParaView output: one VTK UnstructuredGrid (`.vtu`, ASCII) per frame and a
/// `.pvd` collection that lists the frames with their times. Enough for
/// ParaView to play a run back; no VTK dependency.

#include <filesystem>
#include <string>
#include <vector>

#include "sim/mesh/tet_mesh.hpp"

namespace tcb {

struct VtuPointVectors {
  std::string name;                 ///< e.g. "velocity_m_per_s"
  const std::vector<Vec3>* values;  ///< one per vertex
};

void write_vtu(const std::filesystem::path& path, const std::vector<Vec3>& positions_m,
               const std::vector<Tet>& tets, const std::vector<VtuPointVectors>& point_data = {});

struct PvdFrame {
  double time_s;
  std::string file;  ///< relative to the .pvd
};

void write_pvd(const std::filesystem::path& path, const std::vector<PvdFrame>& frames);

}  // namespace tcb
