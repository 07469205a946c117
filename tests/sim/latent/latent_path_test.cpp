// A body driven through a latent path: the path file's rules, interpolation,
// and a world that moves the body to the decoded shape of each step's code.
#include "sim/latent/latent_path.hpp"

#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "sim/world/world_desc.hpp"

using namespace tcb;
namespace fs = std::filesystem;

namespace {

fs::path write_temp(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / ("tcbench_latent_path_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / name) << text;
  return dir / name;
}

// Built with append: GCC 12 warns falsely (-Wrestrict) on string + literal here.
std::string with_header(const char* rows) { return std::string("time_s,z0,z1\n").append(rows); }

}  // namespace

TEST_CASE("latent path: codes interpolated linearly, held outside the samples", "[latent]") {
  const LatentPath p = read_latent_path_csv(write_temp("ok.csv", with_header("0,-1,0\n1,1,0.5\n")), 2);
  CHECK(p.at(-1.0) == Eigen::Vector2d(-1, 0));
  CHECK(p.at(0.5).isApprox(Eigen::Vector2d(0, 0.25)));
  CHECK(p.at(2.0) == Eigen::Vector2d(1, 0.5));
}

TEST_CASE("latent path: malformed files name the file and the line", "[latent]") {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"time_s,z0\n0,1\n", ":1: expected the header time_s,z0,z1"},
      {with_header("0,1\n"), ":2: expected 3 values"},
      {with_header("0,1,2,3\n"), ":2: expected 3 values"},
      {with_header("0,1,1\n0,1,1\n"), ":3: times must increase"},
      {with_header("0,1,inf\n"), ":2: values must be finite"},
      {with_header(""), ":1: no samples"},
  };
  for (const auto& [text, expected] : cases) {
    INFO(text);
    const fs::path path = write_temp("bad.csv", text);
    CHECK_THROWS_WITH(read_latent_path_csv(path, 2), Catch::Matchers::Contains(path.string() + expected));
  }
}

TEST_CASE("a latent-driven body takes the decoded shape of its path's code at every step", "[latent]") {
  const SkinnedFinger finger(finger_preset("finger_small"));
  const Eigen::VectorXd rest = finger.rest_code(), curl = finger.full_curl_code();
  std::string csv = "time_s";
  for (int k = 0; k < 12; ++k) csv.append(",z").append(std::to_string(k));
  csv += "\n0";
  for (int k = 0; k < 12; ++k) csv.append(",").append(std::to_string(rest[k]));
  csv += "\n0.01";
  for (int k = 0; k < 12; ++k) csv.append(",").append(std::to_string(curl[k]));
  csv += "\n";
  const fs::path path = write_temp("curl.csv", csv);
  WorldDesc desc;
  ObjectDesc o;
  o.name = "finger";
  o.mesh = "finger:finger_small";
  o.passive = true;
  o.self_collision = true;
  o.latent_path = path.filename().string();
  o.base_dir = path.parent_path();
  o.position_m = Vec3(0, 1, 0);
  desc.objects.push_back(o);
  World world = build_world(desc);
  REQUIRE(world.bodies.size() == 1);
  const Body& body = world.bodies[0];
  REQUIRE(body.latent);
  CHECK(self_collision_active(body));  // passive, but its shape changes
  CHECK(body.x_m[7] == finger.decode(rest)[7] + Vec3(0, 1, 0));
  world.step(0.005);  // halfway along the path
  const Eigen::VectorXd half = 0.5 * rest + 0.5 * curl;
  CHECK(body.latent_code.isApprox(half));
  const std::vector<Vec3> expected = finger.decode(body.latent_code);
  for (std::size_t i = 0; i < expected.size(); ++i) CHECK(body.x_m[i] == expected[i] + Vec3(0, 1, 0));
  CHECK(body.v_m_per_s[7].isApprox((expected[7] - finger.decode(rest)[7]) / 0.005));
  // A rigidly driven or fixed body cannot come to collide with itself.
  Body fixed;
  fixed.passive = true;
  fixed.self_collision = true;
  CHECK_FALSE(self_collision_active(fixed));
  // A latent path needs a latent family as its mesh.
  desc.objects[0].mesh = "box:size=1x1x1,cells=2x2x2";
  CHECK_THROWS_WITH(build_world(desc), Catch::Matchers::Contains("latent_path needs a latent family"));
  fs::remove_all(path.parent_path());
}
