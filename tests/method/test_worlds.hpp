#pragma once
// Small scenes for the collision tests, built in code.

#include <string>
#include <utility>
#include <vector>

#include "method/handler/collision_settings.hpp"
#include "sim/world/world_desc.hpp"

namespace tcb::test {

struct Placed {
  std::string name, mesh;
  Vec3 position = Vec3::Zero();
  bool passive = false;
  bool self_collision = false;
  double scale = 1.0;
  int stack = 1;
};

/// A world and its collision configuration, as a scene file would give them.
struct TestScene {
  WorldDesc world;
  CollisionDesc collision;
};

inline TestScene scene_of(const std::vector<Placed>& objects, const std::string& data_dir = "") {
  TestScene scene;
  scene.world.dt_s = 1e-3;
  scene.world.gravity_m_per_s2 = Vec3(0, -9.81, 0);
  // The forces these tests check are the explicit ones; implicit response (links)
  // is tested where it is named.
  scene.collision.response_mode = ResponseMode::Explicit;
  // Stable for the lightest vertices of these small meshes (explicit penalty).
  scene.collision.response_stiffness_n_per_m = 100.0;
  for (const Placed& p : objects) {
    ObjectDesc o;
    o.name = p.name;
    o.mesh = p.mesh;
    o.base_dir = data_dir;
    o.position_m = p.position;
    o.passive = p.passive;
    o.self_collision = p.self_collision;
    o.scale = p.scale;
    o.stack.count = p.stack;
    scene.world.objects.push_back(o);
  }
  return scene;
}

/// The scene's world (found by argument-dependent lookup: build_world(scene_of(...))).
inline World build_world(const TestScene& scene) { return tcb::build_world(scene.world); }

/// The collision settings a run would resolve for this scene's world.
inline CollisionSettings settings_of(const World& world, const TestScene& scene) {
  return resolve_collision_settings(world, scene.collision, scene.world.dt_s);
}

/// Small scenes with collisions of every kind the detection must get right,
/// named: overlapping bodies, the face-on-face plate stack, a real mesh pair,
/// a passive obstacle, two passive bodies through each other (a disabled
/// pair), self-collision. The detection tests run over all of them.
inline std::vector<std::pair<std::string, TestScene>> collision_scenes() {
  const std::string data = TCBENCH_DATA_DIR;
  std::vector<std::pair<std::string, TestScene>> s;
  s.emplace_back("two overlapping boxes",
                 scene_of({{"a", "box:size=0.2x0.2x0.2,cells=3x3x3"},
                           {"b", "box:size=0.2x0.2x0.2,cells=4x2x3", Vec3(0.07, 0.05, 0.03)}}));
  s.emplace_back("plate stack, exactly face on face and vertex on vertex",
                 scene_of({{"plate", "box:size=0.3x0.02x0.3,cells=4x2x4", Vec3::Zero(), false, false, 1.0, 4}}));
  s.emplace_back("sphere into torus",
                 scene_of({{"torus", "meshes/torus_coarse.mesh"},
                           {"sphere", "meshes/sphere_fine.mesh", Vec3(0.1, 0.02, 0.0), false, false, 0.5}},
                          data));
  s.emplace_back("passive obstacle", scene_of({{"floor", "box:size=1x0.1x1,cells=5x1x5", Vec3::Zero(), true},
                                               {"cube", "box:size=0.2x0.2x0.2,cells=3x3x3", Vec3(0.1, 0.12, 0.0)}}));
  // Two passive bodies through each other: their pair is disabled, so the
  // wall's vertices inside the floor (and the floor's inside the wall) are
  // no contacts, while both are the cube's partners.
  s.emplace_back("two passive obstacles through each other",
                 scene_of({{"floor", "box:size=1x0.1x1,cells=5x1x5", Vec3::Zero(), true},
                           {"wall", "box:size=0.1x0.4x0.6,cells=1x4x3", Vec3(0.2, 0.1, 0.0), true},
                           {"cube", "box:size=0.2x0.2x0.2,cells=3x3x3", Vec3(-0.1, 0.12, 0.0)}}));
  s.emplace_back("self-collision of a folded pair",
                 scene_of({{"self", "box:size=0.2x0.2x0.2,cells=2x2x2", Vec3::Zero(), false, true},
                           {"other", "box:size=0.2x0.2x0.2,cells=2x2x2", Vec3(0.05, 0.05, 0.05)}}));
  return s;
}

}  // namespace tcb::test
