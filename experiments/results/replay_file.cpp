#include "experiments/results/replay_file.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "sim/mesh/curve_numbering.hpp"

namespace tcb {
namespace {

// A vertex as the file numbers it (sim/mesh/curve_numbering.hpp).
std::int32_t file_vertex_of(const World& world, std::int32_t body, std::int32_t vertex) {
  return file_vertex(*world.bodies[static_cast<std::size_t>(body)].mesh, vertex);
}

}  // namespace

static_assert(std::endian::native == std::endian::little, "replay.bin is written little-endian, natively");

template <class T>
void ReplayWriter::put(const T& value) {
  m_file.stream().write(reinterpret_cast<const char*>(&value), sizeof(T));
  m_bytes += sizeof(T);
}

void ReplayWriter::put_position(const Vec3& p) {
  for (int k = 0; k < 3; ++k) put(static_cast<float>(p[k]));
}

ReplayWriter::ReplayWriter(const std::filesystem::path& dir, const World& world, int every,
                           std::optional<double> debug_cell_size_m)
    : m_dir(dir), m_every(every), m_cell_m(debug_cell_size_m), m_file(dir / "replay.bin") {
  using Json = nlohmann::ordered_json;
  Json bodies = Json::array();
  std::vector<std::uint32_t> triangles;
  std::size_t first_tet = 0;
  for (std::size_t b = 0; b < world.bodies.size(); ++b) {
    const TetMesh& mesh = *world.bodies[b].mesh;
    const auto first_vertex = static_cast<std::uint32_t>(m_surface.size());
    const auto first_triangle = static_cast<std::uint32_t>(triangles.size() / 3);
    std::unordered_map<std::int32_t, std::uint32_t> index;  // mesh vertex -> surface index
    for (const std::int32_t v : mesh.surface_vertices) {
      index[v] = static_cast<std::uint32_t>(m_surface.size());
      m_surface.emplace_back(static_cast<std::uint32_t>(b), static_cast<std::uint32_t>(v));
    }
    for (const Triangle& t : mesh.surface)
      for (int k = 0; k < 3; ++k) triangles.push_back(index.at(t[k]));
    bodies.push_back({{"name", world.bodies[b].name},
                      {"surface_vertices", {first_vertex, m_surface.size() - first_vertex}},
                      {"triangles", {first_triangle, triangles.size() / 3 - first_triangle}},
                      {"tets", {first_tet, mesh.tet_count()}}});
    first_tet += mesh.tet_count();
  }
  m_manifest["schema"] = "tcbench.replay/1";
  m_manifest["every"] = every;
  m_manifest["debug"] = m_cell_m ? nlohmann::ordered_json{{"cell_size_m", *m_cell_m}} : nlohmann::ordered_json(nullptr);
  m_manifest["bodies"] = bodies;
  m_manifest["triangles"] = {{"offset", m_bytes}, {"count", triangles.size() / 3}};
  for (const std::uint32_t i : triangles) put(i);
  m_manifest["surface_map"] = {{"offset", m_bytes}, {"count", m_surface.size()}};
  for (const auto& [body, vertex] : m_surface) {  // vertices in the file's numbering, as every output names them
    put(body);
    put(static_cast<std::uint32_t>(
        file_vertex_of(world, static_cast<std::int32_t>(body), static_cast<std::int32_t>(vertex))));
  }
  m_manifest["layouts"] = {
      {"positions", "float32 x 3 per surface vertex (m)"},
      {"contact",
       {{"bytes", kContactBytes},
        {"fields",
         {{"body", 0, "int32"}, {"vertex", 4, "int32"}, {"other", 8, "int32"}, {"tet", 12, "int32"},
          {"depth_m", 16, "float32"}, {"direction", 20, "float32x3"}, {"position_m", 32, "float32x3"},
          {"force", 44, "uint8"}, {"depth_source", 45, "uint8"}}},
        {"force", {{"0", "computed"}, {"1", "held"}, {"2", "extrapolated"}, {"3", "tracked"}, {"255", "none"}}},
        {"depth_source", {{"0", "none"}, {"1", "border"}, {"2", "propagated"}, {"3", "tet_pair"}}}}},
      {"oracle_point",
       {{"bytes", kOraclePointBytes},
        {"fields",
         {{"body", 0, "int32"}, {"vertex", 4, "int32"}, {"other", 8, "int32"}, {"depth_m", 12, "float32"},
          {"position_m", 16, "float32x3"}}}}},
      {"boundary_point", {{"bytes", 8}, {"fields", {{"body", 0, "int32"}, {"vertex", 4, "int32"}}}}}};
  m_manifest["frames"] = Json::array();
}

void ReplayWriter::record(std::int64_t step, const World& world, const CollisionHandler& handler,
                          const StepReport& report, const OracleFrame* oracle) {
  if (m_every <= 0 || step % m_every != 0) return;
  using Json = nlohmann::ordered_json;
  const std::uint64_t start = m_bytes;
  Json frame = {{"step", step}, {"time_s", world.time_s}, {"positions_offset", m_bytes}};
  for (const auto& [body, vertex] : m_surface) put_position(world.bodies[body].x_m[vertex]);
  // How each point's force was made this step (report.force_points); none: no force.
  std::unordered_map<std::uint64_t, std::uint8_t> source;
  const auto key = [](std::int32_t body, std::int32_t vertex) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(body)) << 32) | static_cast<std::uint32_t>(vertex);
  };
  for (const ForcePoint& f : report.force_points) source[key(f.object, f.vertex)] = static_cast<std::uint8_t>(f.source);
  const std::vector<Contact>& contacts = handler.contacts();
  frame["contacts"] = {{"offset", m_bytes}, {"count", contacts.size()}};
  constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
  for (const Contact& c : contacts) {
    put(c.object), put(file_vertex_of(world, c.object, c.vertex)), put(c.other), put(c.tet);
    put(c.depth_source == DepthSource::None ? kNaN : static_cast<float>(c.depth_m));
    put_position(c.direction);
    put_position(world.bodies[static_cast<std::size_t>(c.object)].x_m[static_cast<std::size_t>(c.vertex)]);
    const auto it = source.find(key(c.object, c.vertex));
    put(it == source.end() ? kNoForce : it->second);
    put(static_cast<std::uint8_t>(c.depth_source));
    put(std::uint16_t{0});
  }
  if (oracle) {
    frame["oracle"] = {{"offset", m_bytes}, {"count", oracle->inside.size()}};
    for (const OraclePoint& p : oracle->inside) {
      put(p.object), put(file_vertex_of(world, p.object, p.vertex)), put(p.other);
      put(static_cast<float>(p.depth_m));
      put_position(world.bodies[static_cast<std::size_t>(p.object)].x_m[static_cast<std::size_t>(p.vertex)]);
    }
    // Touching points: the metrics count a method's point there neither
    // right nor wrong (oracle_comparison.cpp), and so must the viewer.
    frame["boundary"] = {{"offset", m_bytes}, {"count", oracle->boundary.size()}};
    for (const auto& [object, vertex] : oracle->boundary) put(object), put(file_vertex_of(world, object, vertex));
  } else {
    frame["oracle"] = nullptr;
    frame["boundary"] = nullptr;
  }
  if (m_cell_m) put_debug(world, frame);
  frame["bytes"] = m_bytes - start;
  m_manifest["frames"].push_back(std::move(frame));
}

void ReplayWriter::put_debug(const World& world, nlohmann::ordered_json& frame) {
  std::vector<std::array<std::int32_t, 3>> cells;
  bool truncated = false;
  std::uint64_t tets = 0;
  const std::uint64_t aabbs_at = m_bytes;
  const double inverse = 1.0 / *m_cell_m;
  const auto cell = [&](double x) {
    return static_cast<std::int32_t>(std::clamp(std::floor(x * inverse), -2147483648.0, 2147483647.0));
  };
  for (const Body& body : world.bodies) {
    for (const Tet& t : body.mesh->tets) {
      Vec3 lo = body.x_m[static_cast<std::size_t>(t[0])], hi = lo;
      for (int k = 1; k < 4; ++k) {
        lo = lo.cwiseMin(body.x_m[static_cast<std::size_t>(t[k])]);
        hi = hi.cwiseMax(body.x_m[static_cast<std::size_t>(t[k])]);
      }
      put_position(lo);
      put_position(hi);
      ++tets;
      for (std::int32_t i = cell(lo.x()); i <= cell(hi.x()) && !truncated; ++i)
        for (std::int32_t j = cell(lo.y()); j <= cell(hi.y()) && !truncated; ++j)
          for (std::int32_t k = cell(lo.z()); k <= cell(hi.z()) && !truncated; ++k) {
            if (cells.size() >= 4 * kMaxDebugCells) truncated = true;  // before de-duplication
            else cells.push_back({i, j, k});
          }
    }
  }
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
  if (cells.size() > kMaxDebugCells) cells.resize(kMaxDebugCells), truncated = true;
  frame["aabbs"] = {{"offset", aabbs_at}, {"count", tets}};
  frame["cells"] = {{"offset", m_bytes}, {"count", cells.size()}, {"truncated", truncated}};
  for (const auto& c : cells) put(c[0]), put(c[1]), put(c[2]);
}

void ReplayWriter::finish() {
  m_file.commit();
  const std::size_t frames = m_manifest["frames"].size();
  std::uint64_t frame_bytes = 0;
  for (const auto& f : m_manifest["frames"]) frame_bytes += f["bytes"].get<std::uint64_t>();
  m_manifest["bytes"] = m_bytes;
  m_manifest["bytes_per_frame"] = frames ? static_cast<double>(frame_bytes) / static_cast<double>(frames) : 0.0;
  write_file_atomically(m_dir / "replay.json", m_manifest.dump(1) + "\n");
}

}  // namespace tcb
