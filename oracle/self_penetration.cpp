#include "oracle/self_penetration.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "oracle/self_depth.hpp"
#include "oracle/tet_inside.hpp"

namespace tcb {

SelfPenetration self_penetration(const Body& body) {
  const TetMesh& mesh = *body.mesh;
  SelfPenetration r;
  std::int32_t max_part = 0;
  for (const std::int32_t p : mesh.tet_part) {
    if (p < 0) throw std::invalid_argument("self_penetration: negative part " + std::to_string(p));
    max_part = std::max(max_part, p);
  }
  r.part_pd_m.assign(static_cast<std::size_t>(max_part) + 1, 0.0);
  const SelfDepths depths = self_collision_depths(body, classify_self_points(body));
  r.deep = depths.deep;
  r.shallow = depths.shallow;
  r.penetrates = depths.deep > 0;
  if (!r.penetrates) return r;
  for (std::size_t v = 0; v < depths.depth_m.size(); ++v) {
    const double d = depths.depth_m[v];
    if (std::isnan(d)) continue;
    r.pd_m = std::max(r.pd_m, d);
    for (const std::int32_t* t = mesh.vertex_tets.begin(v); t != mesh.vertex_tets.end(v); ++t) {
      double& part = r.part_pd_m[static_cast<std::size_t>(mesh.tet_part[*t])];
      part = std::max(part, d);
    }
  }
  return r;
}

}  // namespace tcb
