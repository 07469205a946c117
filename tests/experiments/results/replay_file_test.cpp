// The replay (--record N): read back through its manifest, it holds the
// surface once, the positions the handler saw (those of trajectory.bin one
// step earlier, at float32), the method's colliding points with how their
// forces were made, and the oracle's inside points where it ran.
#include "experiments/results/replay_file.hpp"

#include <catch2/catch.hpp>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>

#include "experiments/results/trajectory_file.hpp"
#include "experiments/run/provenance.hpp"
#include "experiments/run/run_scene.hpp"
#include "experiments/scene/scene_file.hpp"
#include "sim/io/atomic_file.hpp"
#include "sim/world/world_desc.hpp"

using namespace tcb;
namespace fs = std::filesystem;

namespace {

template <class T>
T at(const std::string& bytes, std::uint64_t offset) {
  T value;
  REQUIRE(offset + sizeof(T) <= bytes.size());
  std::memcpy(&value, bytes.data() + offset, sizeof(T));
  return value;
}

// steps.csv's column `name` at `step` (1-based rows).
std::string cell(const fs::path& csv, const std::string& name, std::int64_t step) {
  std::stringstream in(read_file(csv));
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  for (std::stringstream h(line); std::getline(h, line, ',');) header.push_back(line);
  const auto column = std::find(header.begin(), header.end(), name) - header.begin();
  for (std::int64_t s = 1; std::getline(in, line); ++s) {
    if (s != step) continue;
    std::vector<std::string> cells;
    for (std::stringstream l(line); std::getline(l, line, ',');) cells.push_back(line);
    return static_cast<std::size_t>(column) < cells.size() ? cells[static_cast<std::size_t>(column)] : "";
  }
  return "?";
}

}  // namespace

TEST_CASE("replay: the surface once, then per recorded step positions, contacts and oracle points", "[replay]") {
  const SceneDesc scene = load_scene_file(resolve_scene("two_blocks", default_scene_dirs()));
  RunOptions options;
  options.steps = 20;
  options.record_every = 5;
  options.trajectory_every = 1;
  options.oracle.every = 10;
  options.out_dir = fs::temp_directory_path() / ("tcbench_replay_" + std::to_string(::getpid()));
  fs::remove_all(options.out_dir);
  REQUIRE(run_scene(scene, options).status == "ok");
  const auto manifest = nlohmann::json::parse(read_file(options.out_dir / "replay.json"));
  const std::string bytes = read_file(options.out_dir / "replay.bin");
  CHECK(manifest["schema"] == "tcbench.replay/1");
  CHECK(manifest["bytes"] == bytes.size());
  CHECK_FALSE(fs::exists(options.out_dir / "replay.bin.tmp"));
  const auto run = nlohmann::json::parse(read_file(options.out_dir / "run.json"));
  CHECK(run["replay"]["every"] == 5);

  // The surface, as the meshes have it.
  const World world = build_world(scene.world);
  std::size_t vertices = 0, triangles = 0;
  for (const Body& b : world.bodies) vertices += b.mesh->surface_vertices.size(), triangles += b.mesh->surface.size();
  REQUIRE(manifest["surface_map"]["count"] == vertices);
  REQUIRE(manifest["triangles"]["count"] == triangles);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> map;
  const std::uint64_t map_at = manifest["surface_map"]["offset"];
  for (std::size_t i = 0; i < vertices; ++i)
    map.emplace_back(at<std::uint32_t>(bytes, map_at + 8 * i), at<std::uint32_t>(bytes, map_at + 8 * i + 4));
  const std::uint64_t tri_at = manifest["triangles"]["offset"];
  for (std::size_t t = 0; t < triangles; t += 17) {  // a sample: each corner maps back to the body's triangle
    std::size_t body = 0, first = 0;
    while (t >= first + world.bodies[body].mesh->surface.size()) first += world.bodies[body++].mesh->surface.size();
    for (int k = 0; k < 3; ++k) {
      const auto s = at<std::uint32_t>(bytes, tri_at + 12 * t + 4 * static_cast<std::uint64_t>(k));
      CHECK(map[s].first == body);
      CHECK(static_cast<std::int32_t>(map[s].second) == world.bodies[body].mesh->surface[t - first][k]);
    }
  }

  // Frames at steps 5, 10, 15, 20: the state the handler saw = trajectory.bin one step earlier.
  REQUIRE(manifest["frames"].size() == 4);
  TrajectoryReader trajectory(options.out_dir / "trajectory.bin");
  std::vector<TrajectoryFrame> states;
  while (auto f = trajectory.next()) states.push_back(std::move(*f));
  int contacts_seen = 0, oracle_frames = 0;
  for (const auto& frame : manifest["frames"]) {
    const std::int64_t step = frame["step"];
    INFO("step " << step);
    CHECK(step % 5 == 0);
    const TrajectoryFrame& before = states[static_cast<std::size_t>(step - 2)];  // after step - 1
    REQUIRE(before.step == step - 1);
    const std::uint64_t pos = frame["positions_offset"];
    for (std::size_t i = 0; i < vertices; i += 7) {
      const Vec3& x = before.x_m[map[i].first][map[i].second];
      for (int k = 0; k < 3; ++k)
        CHECK(at<float>(bytes, pos + 12 * i + 4 * static_cast<std::uint64_t>(k)) == static_cast<float>(x[k]));
    }
    const std::uint64_t count = frame["contacts"]["count"];
    CHECK(std::to_string(count) == cell(options.out_dir / "steps.csv", "colliding_points", step));
    for (std::uint64_t c = 0; c < count; ++c) {
      const std::uint64_t rec = frame["contacts"]["offset"].get<std::uint64_t>() + kContactBytes * c;
      const auto force = at<std::uint8_t>(bytes, rec + 44);
      const float depth = at<float>(bytes, rec + 16);
      // `full`: every point with a depth got its force computed this step; one without none.
      CHECK(force == (std::isnan(depth) ? kNoForce : 0));
      ++contacts_seen;
    }
    CHECK(frame["boundary"].is_null() == frame["oracle"].is_null());
    if (frame["oracle"].is_null()) continue;
    ++oracle_frames;
    CHECK(std::to_string(frame["oracle"]["count"].get<std::uint64_t>()) ==
          cell(options.out_dir / "steps.csv", "oracle_points", step));
    // Touching points follow the inside points: valid vertices, none of them inside.
    const std::uint64_t inside_at = frame["oracle"]["offset"], inside = frame["oracle"]["count"];
    const std::uint64_t touching_at = frame["boundary"]["offset"], touching = frame["boundary"]["count"];
    CHECK(touching_at == inside_at + inside * kOraclePointBytes);
    std::set<std::pair<std::int32_t, std::int32_t>> inside_points;
    for (std::uint64_t i = 0; i < inside; ++i)
      inside_points.insert({at<std::int32_t>(bytes, inside_at + i * kOraclePointBytes),
                            at<std::int32_t>(bytes, inside_at + i * kOraclePointBytes + 4)});
    for (std::uint64_t i = 0; i < touching; ++i) {
      const auto body = at<std::int32_t>(bytes, touching_at + 8 * i);
      const auto vertex = at<std::int32_t>(bytes, touching_at + 8 * i + 4);
      REQUIRE((body == 0 || body == 1));
      CHECK(vertex >= 0);
      CHECK_FALSE(inside_points.count({body, vertex}));
    }
  }
  CHECK(contacts_seen > 0);   // the blocks rest on each other
  CHECK(oracle_frames == 2);  // steps 10 and 20
  fs::remove_all(options.out_dir);
}

TEST_CASE("replay --record-debug: every tet's box and the grid cells the boxes overlap", "[replay]") {
  const SceneDesc scene = load_scene_file(resolve_scene("two_blocks", default_scene_dirs()));
  RunOptions options;
  options.steps = 10;
  options.record_every = 10;
  options.record_debug = true;
  options.trajectory_every = 1;
  options.out_dir = fs::temp_directory_path() / ("tcbench_replay_debug_" + std::to_string(::getpid()));
  fs::remove_all(options.out_dir);
  REQUIRE(run_scene(scene, options).status == "ok");
  const auto manifest = nlohmann::json::parse(read_file(options.out_dir / "replay.json"));
  const std::string bytes = read_file(options.out_dir / "replay.bin");
  const double cell_m = manifest["debug"]["cell_size_m"];
  REQUIRE(cell_m > 0.0);
  const World world = build_world(scene.world);
  TrajectoryReader trajectory(options.out_dir / "trajectory.bin");
  std::vector<TrajectoryFrame> states;
  while (auto f = trajectory.next()) states.push_back(std::move(*f));
  const auto& frame = manifest["frames"][0];
  const TrajectoryFrame& before = states[8];  // after step 9: what step 10's handler saw
  REQUIRE(before.step == 9);
  std::size_t tets = 0;
  for (const Body& b : world.bodies) tets += b.mesh->tet_count();
  REQUIRE(frame["aabbs"]["count"] == tets);
  const std::uint64_t cells_at = frame["cells"]["offset"], cell_count = frame["cells"]["count"];
  CHECK_FALSE(frame["cells"]["truncated"].get<bool>());
  std::vector<std::array<std::int32_t, 3>> cells;
  for (std::uint64_t c = 0; c < cell_count; ++c)
    cells.push_back({at<std::int32_t>(bytes, cells_at + 12 * c), at<std::int32_t>(bytes, cells_at + 12 * c + 4),
                     at<std::int32_t>(bytes, cells_at + 12 * c + 8)});
  CHECK(std::is_sorted(cells.begin(), cells.end()));
  CHECK(std::adjacent_find(cells.begin(), cells.end()) == cells.end());
  std::uint64_t rec = frame["aabbs"]["offset"];
  for (std::size_t b = 0; b < world.bodies.size(); ++b)
    for (const Tet& t : world.bodies[b].mesh->tets) {
      Vec3 lo = before.x_m[b][static_cast<std::size_t>(t[0])], hi = lo;
      for (int k = 1; k < 4; ++k)
        lo = lo.cwiseMin(before.x_m[b][static_cast<std::size_t>(t[k])]), hi = hi.cwiseMax(before.x_m[b][static_cast<std::size_t>(t[k])]);
      for (int k = 0; k < 3; ++k) {
        CHECK(at<float>(bytes, rec + 4 * static_cast<std::uint64_t>(k)) == static_cast<float>(lo[k]));
        CHECK(at<float>(bytes, rec + 12 + 4 * static_cast<std::uint64_t>(k)) == static_cast<float>(hi[k]));
      }
      // The cell of the box's centre is among the occupied ones.
      const Vec3 centre = 0.5 * (lo + hi);
      const std::array<std::int32_t, 3> c = {static_cast<std::int32_t>(std::floor(centre.x() / cell_m)),
                                             static_cast<std::int32_t>(std::floor(centre.y() / cell_m)),
                                             static_cast<std::int32_t>(std::floor(centre.z() / cell_m))};
      CHECK(std::binary_search(cells.begin(), cells.end(), c));
      rec += 24;
    }
  fs::remove_all(options.out_dir);
}
