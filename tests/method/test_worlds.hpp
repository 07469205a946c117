#pragma once
// Small scenes for the collision tests, built in code.

#include <string>
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

}  // namespace tcb::test
