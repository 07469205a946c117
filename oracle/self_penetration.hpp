#pragma once
/// A body's self-penetration as one label: the exact answer the neural
/// self-collision detector (seed 002) learns and is judged by. Built on the
/// part-aware true depths of self_depth.hpp (CGAL only; independent of
/// method/).
///
/// Contract:
/// - a body *penetrates itself* when at least one vertex is deep: inside, by
///   the exact rule of classify_self_points (tet_inside.hpp), tets of a part
///   outside its own neighbourhood (its incident tets' parts and the parts
///   touching them; self_depth.hpp), with a boundary triangle of those far
///   parts to measure to. A vertex that only touches a far tet's boundary
///   face on the surface is not inside and does not count;
/// - its penetration depth pd_m is the largest true depth over the deep
///   vertices (metres; 0 when none). This is a vertex depth to the far parts'
///   surface, not the paper's minimal-translation PD: it is exact, cheap and
///   zero exactly on the collision-free set, which is what the labels need;
/// - per part a, part_pd_m[a] is the largest depth among the deep vertices of
///   a tet of part a (a vertex on a cut between parts counts for each of its
///   parts); parts are indexed 0..max(tet_part); 0 when none of a's vertices
///   is deep; a negative part is std::invalid_argument (part ids index the
///   result: keep them small, as MEDIT references and box parts are);
/// - a body with fewer than two parts never penetrates itself (no part can
///   be far from another).
/// Cost: one exact self classification plus one distance tree per group of
/// deep vertices sharing a neighbourhood.

#include <cstdint>
#include <vector>

#include "sim/world/world.hpp"

namespace tcb {

struct SelfPenetration {
  bool penetrates = false;
  double pd_m = 0.0;               ///< largest true depth over the deep vertices
  std::vector<double> part_pd_m;   ///< per part (index = tet_part value)
  std::int64_t deep = 0;           ///< vertices with a true depth
  std::int64_t shallow = 0;        ///< self-collision points inside their own neighbourhood only
};

/// The self-penetration of `body` at its current positions x_m.
SelfPenetration self_penetration(const Body& body);

}  // namespace tcb
