#pragma once
/// The replay of a run (--record N), for viewers: DIR/replay.bin and
/// DIR/replay.json, beside the VTU frames. Little-endian; every offset and
/// count is in replay.json, which says what each buffer holds:
///
///   once:  triangles   uint32 x 3 per surface triangle (outward), indices
///                      into the surface vertices of all bodies in order
///          surface_map uint32 x 2 per surface vertex: body, vertex
///   per recorded frame (the state the handler saw at that step: before the
///   step's dynamics; step 0 is not recorded):
///          positions   float32 x 3 per surface vertex (m)
///          contacts    kContactBytes per colliding point the method holds
///                      (contacts()): int32 body, vertex, other, tet;
///                      float32 depth_m (NaN without a depth), direction[3],
///                      position_m[3]; uint8 force (ForceSource: 0 computed,
///                      1 held, 2 extrapolated, 3 tracked; 255 none: no
///                      force this step), uint8 depth_source (Contact's
///                      DepthSource), 2 bytes padding
///          oracle      kOraclePointBytes per point the oracle finds inside
///                      (only on frames where the oracle ran): int32 body,
///                      vertex, other; float32 depth_m (NaN: no true depth),
///                      position_m[3]
///          boundary    int32 x 2 (body, vertex) per point the oracle finds
///                      exactly on another body's surface and inside none
///                      (same frames): touching, counted neither way by
///                      recall and precision
/// Every vertex index written (surface_map, contacts, oracle, boundary) is
/// in the mesh file's numbering, also when the run renumbered its vertices
/// (scene mesh_order "curve", sim/mesh/curve_numbering.hpp); tets are never
/// renumbered.
/// With --record-debug (debug_cell_size_m set), per frame also:
///          aabbs       float32 x 6 per tet of every body in order (min xyz,
///                      max xyz; m): the tets' boxes at the frame's positions
///          cells       int32 x 3 per grid cell some tet's box overlaps
///                      (sorted, unique; cell = floor(x / cell_size_m)): the
///                      cells the run's hash would fill at these positions
///                      (a budgetless cycle's hash leaves out the tets no
///                      query point reaches; their cells are still here).
///                      Recomputed here, not read from the method: an
///                      interruptible cycle may hold a hash of older
///                      positions. At most kMaxDebugCells a frame
///                      (cells_truncated says when more were cut).
/// replay.json: {schema "tcbench.replay/1", every, bodies [{name,
/// surface_vertices: [first, count], triangles: [first, count]}],
/// triangles {offset, count}, surface_map {offset, count}, layouts (the
/// records' fields, byte offsets and types), frames [{step, time_s,
/// positions_offset, contacts {offset, count}, oracle {offset, count} or
/// null, boundary {offset, count} or null}], bytes, bytes_per_frame}.
/// replay.bin is streamed to replay.bin.tmp and renamed when the run ends
/// (stable or not); replay.json is written then, atomically.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "method/handler/collision_handler.hpp"
#include "oracle/inside_oracle.hpp"
#include "sim/io/atomic_file.hpp"
#include "sim/world/world.hpp"

namespace tcb {

inline constexpr std::size_t kContactBytes = 48;
inline constexpr std::size_t kOraclePointBytes = 28;
inline constexpr std::uint8_t kNoForce = 255;
inline constexpr std::size_t kMaxDebugCells = std::size_t{1} << 22;

class ReplayWriter {
 public:
  /// Writes the surface once; frames follow every `every` steps. With
  /// debug_cell_size_m, frames also hold the tets' boxes and occupied cells.
  ReplayWriter(const std::filesystem::path& dir, const World& world, int every,
               std::optional<double> debug_cell_size_m = std::nullopt);
  /// Records the frame of `step` (1-based, as steps.csv counts) when due.
  void record(std::int64_t step, const World& world, const CollisionHandler& handler, const StepReport& report,
              const OracleFrame* oracle);
  /// Renames replay.bin into place and writes replay.json.
  void finish();

 private:
  template <class T>
  void put(const T& value);
  void put_position(const Vec3& p);

  void put_debug(const World& world, nlohmann::ordered_json& frame);

  std::filesystem::path m_dir;
  int m_every;
  std::optional<double> m_cell_m;
  AtomicFile m_file;
  std::uint64_t m_bytes = 0;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> m_surface;  ///< (body, vertex) per surface vertex
  nlohmann::ordered_json m_manifest;
};

}  // namespace tcb
