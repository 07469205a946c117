#pragma once
// Small scenes for the collision tests, built in code.

#include <string>
#include <vector>

#include "sim/world/scene.hpp"

namespace tcb::test {

struct Placed {
  std::string name, mesh;
  Vec3 position = Vec3::Zero();
  bool passive = false;
  bool self_collision = false;
  double scale = 1.0;
  int stack = 1;
};

inline SceneDesc scene_of(const std::vector<Placed>& objects, const std::string& data_dir = "") {
  SceneDesc scene;
  scene.dt_s = 1e-3;
  scene.gravity_m_per_s2 = Vec3(0, -9.81, 0);
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
    scene.objects.push_back(o);
  }
  return scene;
}

}  // namespace tcb::test
