#include "method/handler/collision_settings.hpp"

#include <fmt/format.h>

#include <cmath>

#include "method/detection/spatial_hash.hpp"
#include "sim/io/input_error.hpp"

namespace tcb {

double average_edge_length(const World& world) {
  double sum = 0.0;
  std::size_t count = 0;
  for (const Body& b : world.bodies) {
    for (const Edge& e : b.mesh->edges) sum += (b.x_m[e[1]] - b.x_m[e[0]]).norm();
    count += b.mesh->edges.size();
  }
  return count ? sum / static_cast<double>(count) : 1.0;
}

CollisionSettings resolve_collision_settings(const World& world, const CollisionDesc& desc, double dt_s,
                                             const std::string& file) {
  CollisionSettings s;
  s.mean_edge_m = average_edge_length(world);
  s.detection.cell_size_m = desc.cell_size_m.value_or(desc.cell_size_auto_factor * s.mean_edge_m);
  if (!(s.detection.cell_size_m > 0.0)) s.detection.cell_size_m = 1.0;  // a world of points only
  // "auto*K" with a tiny K (or a tiny world) can make a size whose inverse
  // overflows, which the hash refuses: bad input, said here with the file.
  if (!std::isfinite(s.detection.cell_size_m) || !std::isfinite(1.0 / s.detection.cell_size_m))
    throw InputError(file, 0,
                     fmt::format("collision.cell_size = {:g} m: its inverse is not a finite number; use a larger cell "
                                 "size (or \"auto\": the mean edge, {:g} m)",
                                 s.detection.cell_size_m, s.mean_edge_m));
  // A cell size so small that a tet of the initial world already spans more
  // cells than the hash takes (kMaxCellsPerBox) is bad input, not a run that
  // goes unstable at its first step.
  for (const Body& b : world.bodies) {
    for (const Tet& t : b.mesh->tets) {
      Vec3 lo = b.x_m[t[0]], hi = lo;
      for (int k = 1; k < 4; ++k) {
        lo = lo.cwiseMin(b.x_m[t[k]]);
        hi = hi.cwiseMax(b.x_m[t[k]]);
      }
      double cells = 1.0;
      for (int k = 0; k < 3; ++k) cells *= std::floor(hi[k] / s.detection.cell_size_m) - std::floor(lo[k] / s.detection.cell_size_m) + 1.0;
      if (!(cells <= static_cast<double>(kMaxCellsPerBox)))
        throw InputError(file, 0,
                         fmt::format("collision.cell_size = {:g} m: a tet of object '{}' spans {:.3g} hash cells, more "
                                     "than the {} a box may; use a larger cell size (or \"auto\": the mean edge, {:g} m)",
                                     s.detection.cell_size_m, b.name, cells, kMaxCellsPerBox, s.mean_edge_m));
    }
  }
  for (const Body& b : world.bodies) s.tets += b.mesh->tet_count();
  // 2 K tets + 1, rounded down before the prime search: K = 1 is the
  // detector's own default, next_prime(2 tets + 1).
  const double automatic = std::floor(2.0 * desc.table_size_auto_factor * static_cast<double>(s.tets)) + 1.0;
  if (!desc.table_size && !(automatic <= 4294967296.0))
    throw InputError(file, 0, fmt::format("collision.table_size = \"auto*{:g}\" asks for {:.3g} buckets; at most 2^32",
                                          desc.table_size_auto_factor, automatic));
  s.detection.table_size =
      desc.table_size ? desc.table_size
                      : static_cast<std::size_t>(next_prime(static_cast<std::uint64_t>(automatic)));
  s.detection.hash = desc.hash;
  s.dt_s = dt_s;
  s.response_mode = desc.response_mode;
  s.threads = desc.threads;
  if (s.response_mode == ResponseMode::Implicit)
    for (const Body& b : world.bodies)
      if (!b.passive && b.material.model == MaterialModel::MassSpring && b.material.integrator != Integrator::EulerCromer)
        throw InputError(file, 0,
                         "collision.response = \"implicit\" puts contacts into a linear step, which object '" + b.name +
                             "' (mass_spring with " + to_string(b.material.integrator) +
                             ") does not have: use integrator = \"euler_cromer\" or collision.response = \"explicit\"");
  s.body_count = world.bodies.size();
  const ResponseParams defaults{desc.response_stiffness_n_per_m, desc.damping_n_s_per_m, desc.friction};
  s.pair_response.assign(s.body_count * s.body_count, defaults);
  const auto matches = [&](const Body& b, const std::string& name) { return b.name == name || b.group == name; };
  for (const CollisionPairDesc& pair : desc.pairs) {
    bool found_a = false, found_b = false;
    for (std::size_t a = 0; a < s.body_count; ++a) {
      found_a |= matches(world.bodies[a], pair.a);
      found_b |= matches(world.bodies[a], pair.b);
      for (std::size_t b = 0; b < s.body_count; ++b) {
        const bool hit = (matches(world.bodies[a], pair.a) && matches(world.bodies[b], pair.b)) ||
                         (matches(world.bodies[a], pair.b) && matches(world.bodies[b], pair.a));
        if (!hit) continue;
        ResponseParams& r = s.pair_response[a * s.body_count + b];
        if (pair.stiffness_n_per_m) r.stiffness_n_per_m = *pair.stiffness_n_per_m;
        if (pair.damping_n_s_per_m) r.damping_n_s_per_m = *pair.damping_n_s_per_m;
        if (pair.friction) r.friction = *pair.friction;
      }
    }
    if (!found_a || !found_b)
      throw InputError(file, pair.source_line,
                       "collision.pair names no object '" + (found_a ? pair.b : pair.a) + "'");
  }

  // Explicit penalty forces: a spring of stiffness k on mass m is stable only
  // for k < 4 m / dt^2. Check each colliding pair's lightest vertex. Implicit
  // response has no such bound.
  if (s.response_mode == ResponseMode::Implicit) return s;
  const CollisionPairs pairs(world);
  std::vector<double> lightest(s.body_count, 0.0);
  for (std::size_t b = 0; b < s.body_count; ++b) {
    double m_min = 0.0;
    for (double m : world.bodies[b].mass_kg)
      if (m > 0.0 && (m_min == 0.0 || m < m_min)) m_min = m;
    lightest[b] = world.bodies[b].passive ? 0.0 : m_min;
  }
  double worst_ratio = 0.0;
  std::string worst;
  for (std::size_t a = 0; a < s.body_count; ++a)
    for (std::size_t b = 0; b < s.body_count; ++b) {
      if (!pairs.enabled(a, b)) continue;
      const double m = std::max(lightest[a], lightest[b]) > 0.0
                           ? (lightest[a] > 0.0 && lightest[b] > 0.0 ? std::min(lightest[a], lightest[b])
                                                                     : std::max(lightest[a], lightest[b]))
                           : 0.0;
      if (m == 0.0) continue;
      const double bound = 4.0 * m / (dt_s * dt_s);
      const double ratio = s.response(a, b).stiffness_n_per_m / bound;
      if (ratio > 1.0 && ratio > worst_ratio) {
        worst_ratio = ratio;
        worst = fmt::format(
            "response stiffness {:.4g} N/m between '{}' and '{}' exceeds the explicit stability bound 4 m / dt^2 = "
            "{:.4g} N/m of their lightest vertex ({:.3g} kg at dt {:.3g} s): contacts there may chatter or explode",
            s.response(a, b).stiffness_n_per_m, world.bodies[a].name, world.bodies[b].name, bound, m, dt_s);
      }
    }
  if (!worst.empty()) s.warnings.push_back(worst);
  return s;
}

}  // namespace tcb
