#include "sim/world/trajectory.hpp"

#include <catch2/catch.hpp>

#include <unistd.h>

#include "sim/io/atomic_file.hpp"
#include "tests/remove_on_exit.hpp"
#include "sim/io/input_error.hpp"
#include "sim/world/world_desc.hpp"

using namespace tcb;
namespace fs = std::filesystem;

namespace {

fs::path csv_path() { return fs::temp_directory_path() / ("tcbench_path_" + std::to_string(::getpid()) + ".csv"); }

fs::path write_csv(const std::string& text) {
  write_file_atomically(csv_path(), text);
  return csv_path();
}


}  // namespace

TEST_CASE("trajectory: linear between samples, held outside them", "[trajectory]") {
  const test::RemoveOnExit cleanup{csv_path()};  // passed or failed
  const Trajectory t = read_trajectory_csv(write_csv("time_s,x_m,y_m,z_m\n0,0,1,0\n0.5,1,1,0\n1.0,1,0,2\n"));
  CHECK(t.at(-1.0) == Vec3(0, 1, 0));
  CHECK(t.at(0.25).isApprox(Vec3(0.5, 1, 0)));
  CHECK(t.at(0.75).isApprox(Vec3(1, 0.5, 1)));
  CHECK(t.at(0.5) == Vec3(1, 1, 0));
  CHECK(t.at(7.0) == Vec3(1, 0, 2));
}

TEST_CASE("trajectory: malformed files name the file and the line", "[trajectory]") {
  const test::RemoveOnExit cleanup{csv_path()};  // passed or failed
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"t,x,y,z\n0,0,0,0\n", ":1: expected the header"},
      {"time_s,x_m,y_m,z_m\n0,0,0\n", ":2: expected 4 values"},
      {"time_s,x_m,y_m,z_m\n0,0,0,0,0\n", ":2: expected 4 values"},
      {"time_s,x_m,y_m,z_m\n0,0,0,0\n0,1,1,1\n", ":3: times must increase"},
      {"time_s,x_m,y_m,z_m\n0,0,a,0\n", ":2: 'a' is not a number"},
      {"time_s,x_m,y_m,z_m\n0,0,nan,0\n", ":2: values must be finite"},
      {"time_s,x_m,y_m,z_m\n", ":1: no samples"},
  };
  for (const auto& [text, expected] : cases) {
    INFO(text);
    const fs::path path = write_csv(text);
    CHECK_THROWS_WITH(read_trajectory_csv(path), Catch::Matchers::Contains(path.string() + expected));
  }
}

TEST_CASE("a driven body follows its trajectory with the velocity of that motion, never integrated", "[trajectory]") {
  const test::RemoveOnExit cleanup{csv_path()};  // passed or failed
  WorldDesc scene;
  ObjectDesc probe;
  probe.name = "probe";
  probe.mesh = "box:size=0.1x0.1x0.1,cells=1x1x1";
  probe.passive = true;
  probe.base_dir = fs::temp_directory_path();
  probe.trajectory = write_csv("time_s,x_m,y_m,z_m\n0,0,1,0\n1,0,0,0\n").filename().string();
  scene.objects.push_back(probe);
  World world = build_world(scene);
  Body& b = world.bodies[0];
  REQUIRE(b.trajectory);
  CHECK(b.x_m[0].y() == Approx(1.0 - 0.05));
  for (int s = 0; s < 250; ++s) world.step(1e-3);
  CHECK(b.x_m[0].y() == Approx(0.75 - 0.05));  // gravity does not act on it
  CHECK(b.v_m_per_s[0].isApprox(Vec3(0, -1, 0)));
  b.contact_force_n[3] = Vec3(1, 2, 3);
  b.contact_force_n[5] = Vec3(1, 0, 0);
  world.step(1e-3);  // the force a step applied is what the device renders
  CHECK(*world.driven_contact_force_n() == Vec3(2, 2, 3));
  CHECK(b.contact_force_n[3] == Vec3::Zero());  // cleared for the next step
  World plain;
  CHECK_FALSE(plain.driven_contact_force_n().has_value());
}
