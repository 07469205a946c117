// trajectory.bin: written and read back at float32 precision; a file that is
// not a trajectory, a truncated frame and counts larger than the file are
// input errors, never allocations.
#include "experiments/results/trajectory_file.hpp"

#include <catch2/catch.hpp>

#include <unistd.h>

#include "sim/io/input_error.hpp"
#include "sim/world/world_desc.hpp"

using namespace tcb;
namespace fs = std::filesystem;

namespace {

World two_boxes() {
  WorldDesc desc;
  for (const char* name : {"a", "b"}) {
    ObjectDesc o;
    o.name = name;
    o.mesh = "box:size=0.1x0.1x0.1,cells=2x1x1";
    o.position_m = Vec3(name[0] == 'a' ? 0.0 : 0.3, 0.2, 0.0);
    desc.objects.push_back(o);
  }
  return build_world(desc);
}

fs::path temp(const std::string& name) {
  return fs::temp_directory_path() / ("tcbench_traj_" + name + "_" + std::to_string(::getpid()) + ".bin");
}

}  // namespace

TEST_CASE("trajectory.bin: every K-th step, read back as float32", "[trajectory]") {
  const fs::path path = temp("round");
  World world = two_boxes();
  {
    TrajectoryWriter writer(path, world, 2);
    for (int s = 0; s < 5; ++s) {
      world.step(1e-3);
      writer.write_step(world);  // steps 2 and 4
    }
    writer.commit();
  }
  TrajectoryReader reader(path);
  CHECK(reader.every() == 2);
  REQUIRE(reader.masses_kg().size() == 2);
  CHECK(reader.masses_kg()[0] == world.bodies[0].mass_kg);
  const auto first = reader.next();
  REQUIRE(first);
  CHECK(first->step == 2);
  const auto second = reader.next();
  REQUIRE(second);
  CHECK(second->step == 4);
  CHECK_FALSE(reader.next());
  // Step 5's state is not in the file; step 4's is world's before the last step: compare the layout instead.
  std::vector<float> buffer;
  std::vector<Vec3> rounded;
  as_float32(world.bodies[1].x_m, buffer, rounded);
  CHECK(rounded.size() == second->x_m[1].size());
  for (std::size_t i = 0; i < rounded.size(); ++i) CHECK((rounded[i] - second->x_m[1][i]).norm() < 1e-3);
  fs::remove(path);
}

TEST_CASE("trajectory.bin: not a trajectory, truncated, or counts beyond the file", "[trajectory]") {
  const fs::path path = temp("bad");
  const auto write = [&](const std::string& bytes) {
    std::ofstream out(path, std::ios::binary);
    out << bytes;
  };
  write("not a trajectory at all");
  CHECK_THROWS_AS(TrajectoryReader(path), InputError);
  // The right magic, then a body claiming 2^32-1 masses in a 20-byte file.
  std::string header = "TCBTRJ01";
  const std::uint32_t every = 1, bodies = 1, huge = 0xFFFFFFFFu;
  header.append(reinterpret_cast<const char*>(&every), 4);
  header.append(reinterpret_cast<const char*>(&bodies), 4);
  header.append(reinterpret_cast<const char*>(&huge), 4);
  write(header);
  CHECK_THROWS_WITH(TrajectoryReader(path), Catch::Matchers::Contains("invalid trajectory header"));
  // A real file cut inside its last frame.
  World world = two_boxes();
  {
    TrajectoryWriter writer(path, world, 1);
    world.step(1e-3);
    writer.write_step(world);
    writer.commit();
  }
  fs::resize_file(path, fs::file_size(path) - 5);
  TrajectoryReader reader(path);
  CHECK_THROWS_WITH(reader.next(), Catch::Matchers::Contains("truncated frame at step 1"));
  CHECK_THROWS_AS(TrajectoryReader(temp("missing")), InputError);
  fs::remove(path);
}
