#pragma once
/// trajectory.bin (--trajectory K): every body's positions and velocities
/// every K steps, compact, for comparing a run with a reference run
/// (experiments/metrics/divergence_meter.hpp). Little-endian, in order:
///   "TCBTRJ01"                       8 bytes, the format and its version
///   uint32 every, uint32 body_count
///   per body: uint32 vertex_count, float64 mass_kg[vertex_count]
///   per frame (steps K, 2K, ... after the step, as steps.csv counts):
///     int64 step, then per body float32 x_m[3 n], float32 v_m_per_s[3 n]
/// Vertices are in the mesh file's numbering, also when the run renumbered
/// them (scene mesh_order "curve", sim/mesh/curve_numbering.hpp).
/// float32 keeps a 0.4 m coordinate to about 3e-8 m: the floor of any
/// distance read from this file. Written to trajectory.bin.tmp and renamed
/// when the run finishes (stable or not), like steps.csv.

#include <array>
#include <bit>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <vector>

#include "sim/io/atomic_file.hpp"
#include "sim/world/world.hpp"

namespace tcb {

static_assert(std::endian::native == std::endian::little, "trajectory.bin is written little-endian, natively");

/// `in` rounded to float32 and widened back: what the file holds. Through a
/// float buffer, not `(double)(float)x` in one loop: GCC 12.2 at -O3 with
/// tree vectorization returned that round trip unrounded in a 10-line test
/// here (-O2, or -O3 -fno-tree-vectorize, rounded), which made a run differ
/// from its own trajectory by float32's rounding.
void as_float32(const std::vector<Vec3>& in, std::vector<float>& buffer, std::vector<Vec3>& out);

class TrajectoryWriter {
 public:
  TrajectoryWriter(const std::filesystem::path& path, const World& world, int every);
  /// Appends the world's state when its step is a multiple of `every`.
  void write_step(const World& world);
  void commit() { m_file.commit(); }

 private:
  AtomicFile m_file;
  int m_every;
  std::vector<float> m_scratch;
  std::vector<Vec3> m_file_order;  ///< a renumbered body's values in its file's order
};

struct TrajectoryFrame {
  std::int64_t step = 0;
  std::vector<std::vector<Vec3>> x_m, v_m_per_s;  // per body, widened back to double
};

class TrajectoryReader {
 public:
  /// Reads the header; InputError naming the file when it is not a trajectory
  /// (counts are bounded by the file's size before anything is allocated).
  explicit TrajectoryReader(const std::filesystem::path& path);
  int every() const { return m_every; }
  const std::vector<std::vector<double>>& masses_kg() const { return m_masses; }
  /// The next frame; nullopt at the end (InputError on a truncated frame).
  std::optional<TrajectoryFrame> next();

 private:
  std::filesystem::path m_path;
  std::ifstream m_in;
  std::uintmax_t m_size = 0;
  int m_every = 0;
  std::vector<std::vector<double>> m_masses;
  std::vector<float> m_scratch;
};

}  // namespace tcb
