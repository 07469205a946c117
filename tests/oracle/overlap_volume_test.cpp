#include "oracle/overlap_volume.hpp"

#include <catch2/catch.hpp>

#include "sim/mesh/load_mesh.hpp"
#include "tests/method/test_worlds.hpp"

using namespace tcb;

TEST_CASE("overlap volume: two boxes overlapping by a known box", "[oracle]") {
  // A = [-0.1, 0.1]^3, B = [0, 0.2]^3: the overlap is [0, 0.1]^3, 1e-3 m^3.
  const World world = build_world(test::scene_of({{"a", "box:size=0.2x0.2x0.2,cells=4x4x4"},
                                                  {"b", "box:size=0.2x0.2x0.2,cells=3x3x3", Vec3(0.1, 0.1, 0.1)}}));
  const OverlapFrame frame = compute_overlap_volumes(world);
  CHECK(frame.invalid.empty());
  REQUIRE(frame.pairs.size() == 1);
  CHECK(frame.pairs[0].volume_m3 == Approx(1e-3).epsilon(1e-12));
  CHECK(frame.total_m3 == frame.pairs[0].volume_m3);
  CHECK(enclosed_volume_m3(world.bodies[0]) == Approx(8e-3).epsilon(1e-12));
}

TEST_CASE("overlap volume: a small box wholly inside a large one", "[oracle]") {
  const World world = build_world(test::scene_of(
      {{"big", "box:size=1x1x1,cells=2x2x2", Vec3::Zero(), true}, {"small", "box:size=0.2x0.2x0.2,cells=2x2x2"}}));
  const OverlapFrame frame = compute_overlap_volumes(world);
  REQUIRE(frame.pairs.size() == 1);
  CHECK(frame.pairs[0].volume_m3 == Approx(8e-3).epsilon(1e-12));
}

TEST_CASE("overlap volume: plates resting face on face overlap in zero volume, at no cost", "[oracle]") {
  const World world = build_world(test::scene_of(
      {{"plate", "box:size=0.25x0.0625x0.25,cells=2x1x2", Vec3(0, 0.03125, 0), false, false, 1.0, 3}}));
  const OverlapFrame frame = compute_overlap_volumes(world);
  CHECK(frame.invalid.empty());
  CHECK(frame.pairs.empty());  // touching boxes: no corefinement needed
  CHECK(frame.total_m3 == 0.0);
}

TEST_CASE("overlap volume: a surface that fails the guard gives no value, with the reason", "[oracle]") {
  // dog.mesh's folds leave its surface open.
  // The box (40 units wide) straddles one of the dog's vertices.
  const World world = build_world(test::scene_of({{"dog", std::string(TCBENCH_SHARED_MESHES) + "/dog.mesh"},
                                                  {"box", "box:size=40x40x40,cells=2x2x2", Vec3(24.4, 70.0, -72.6)}}));
  const OverlapFrame frame = compute_overlap_volumes(world);
  CHECK(frame.pairs.empty());
  REQUIRE(frame.invalid.size() == 1);
  CHECK_THAT(frame.invalid[0], Catch::Matchers::Contains("'dog'"));
  CHECK(std::isnan(enclosed_volume_m3(world.bodies[0])));
}
