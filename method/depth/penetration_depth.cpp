#include "method/depth/penetration_depth.hpp"

#include <algorithm>
#include <cmath>

#include "method/geometry/perturbed_predicates.hpp"
#include "method/handler/heap_bytes.hpp"
#include "method/handler/work_units.hpp"

namespace tcb {

SurfaceHash::SurfaceHash(const World& world, double cell_size_m, HashFunction hash) {
  std::uint32_t total = 0;
  for (std::size_t b = 0; b < world.bodies.size(); ++b) {
    m_offset.push_back(total);
    const auto n = world.bodies[b].mesh->surface.size();
    total += static_cast<std::uint32_t>(n);
  }
  m_offset.push_back(total);
  m_hash = SpatialHash(cell_size_m, next_prime(2 * std::size_t(total) + 1), hash);
  m_boxes.resize(total);
}

std::size_t SurfaceHash::memory_bytes() const {
  return m_hash.memory_bytes() + heap_bytes(m_offset) + heap_bytes(m_boxes);
}

void SurfaceHash::triangle_box(const World& world, std::int32_t body, std::int32_t triangle, Vec3& lo,
                               Vec3& hi) const {
  const auto& x = world.bodies[body].x_m;
  const Triangle& f = world.bodies[body].mesh->surface[triangle];
  lo = x[f[0]].cwiseMin(x[f[1]]).cwiseMin(x[f[2]]);
  hi = x[f[0]].cwiseMax(x[f[1]]).cwiseMax(x[f[2]]);
}

std::uint64_t SurfaceHash::hash_triangle(const World& world, std::int32_t body, std::int32_t triangle) {
  const std::uint32_t id = m_offset[body] + static_cast<std::uint32_t>(triangle);
  Box& box = m_boxes[id];
  triangle_box(world, body, triangle, box.lo, box.hi);
  note_hash_step(world.step_index);
  note_insert(id);
  return work::kCellInsert * m_hash.insert_box(box.lo, box.hi, id);
}

double SurfaceHash::triangle_work(const World& world, std::int32_t body, std::int32_t triangle) const {
  Vec3 lo, hi;
  triangle_box(world, body, triangle, lo, hi);
  return static_cast<double>(work::kCellInsert) * m_hash.cells_of_box(lo, hi);
}

std::vector<std::size_t> SurfaceHash::walk_starts(const World& world, const std::vector<std::int32_t>& bodies) {
  std::vector<std::size_t> first(bodies.size() + 1, 0);
  for (std::size_t k = 0; k < bodies.size(); ++k)
    first[k + 1] = first[k] + world.bodies[static_cast<std::size_t>(bodies[k])].mesh->surface.size();
  return first;
}

std::size_t SurfaceHash::body_at(const std::vector<std::size_t>& first, std::size_t i) {
  return static_cast<std::size_t>(std::upper_bound(first.begin() + 1, first.end(), i) - (first.begin() + 1));
}

std::size_t SurfaceHash::triangle_count(const World& world, const std::vector<std::int32_t>& bodies) {
  return walk_starts(world, bodies).back();
}

void SurfaceHash::hash_all(const World& world, const std::vector<std::int32_t>& bodies, WorkerPool& pool,
                           std::vector<std::uint64_t>& work) {
  const std::vector<std::size_t> first = walk_starts(world, bodies);
  work.assign(first.back(), 0);
  // Each part walks its range ascending: its body found once, then stepped
  // (a search a triangle cost plates20's 20 bodies more than the owners'
  // build saved). A part's cursor a cache line apart from the others'.
  struct alignas(64) Cursor {
    std::size_t k = std::numeric_limits<std::size_t>::max();
  };
  std::vector<Cursor> cursor(static_cast<std::size_t>(pool.threads()));
  const auto box_of = [&](int part, std::size_t i, Vec3& lo, Vec3& hi, std::uint32_t& item) {
    std::size_t& k = cursor[static_cast<std::size_t>(part)].k;
    if (k == std::numeric_limits<std::size_t>::max()) k = body_at(first, i);
    while (i >= first[k + 1]) ++k;
    const std::int32_t body = bodies[k];
    const auto triangle = static_cast<std::int32_t>(i - first[k]);
    triangle_box(world, body, triangle, lo, hi);
    item = m_offset[static_cast<std::size_t>(body)] + static_cast<std::uint32_t>(triangle);
    m_boxes[item] = Box{lo, hi};
    return true;
  };
  if (first.back() > 0) note_hash_step(world.step_index);
  // Each body's triangles go in ascending and its ids are contiguous, so
  // noting its lowest and highest id in walk order notes what as many
  // hash_triangle() calls would (ascending overall when `bodies` ascends,
  // the cycle's order); the parallel build keeps every bucket's order.
  for (std::size_t k = 0; k + 1 < first.size(); ++k) {
    if (first[k + 1] == first[k]) continue;
    const std::uint32_t lowest = m_offset[static_cast<std::size_t>(bodies[k])];
    note_insert(lowest);
    note_insert(lowest + static_cast<std::uint32_t>(first[k + 1] - first[k] - 1));
  }
  // Each triangle's cells as its insertion counted them: its work, as
  // hash_triangle() charges it (an absurd box throws there, and no work is read).
  m_hash.insert_all_and_build(first.back(), box_of, pool, SpatialHash::kBucketsPerOwner, work.data());
  for (std::uint64_t& w : work) w *= work::kCellInsert;
}

double SurfaceHash::work_of_all(const World& world, const std::vector<std::int32_t>& bodies, WorkerPool& pool) const {
  const std::vector<std::size_t> first = walk_starts(world, bodies);
  std::vector<double> part_work(static_cast<std::size_t>(pool.threads()), 0.0);
  pool.for_ranges(first.back(), [&](int part, std::size_t begin, std::size_t end) {
    double sum = 0.0;
    for (std::size_t i = begin, k = body_at(first, begin); i < end; ++i) {
      while (i >= first[k + 1]) ++k;
      sum += triangle_work(world, bodies[k], static_cast<std::int32_t>(i - first[k]));
    }
    part_work[static_cast<std::size_t>(part)] = sum;
  });
  double total = 0.0;
  for (const double w : part_work) total += w;
  return total;
}

std::uint64_t border_edge_crossing(const World& world, const Contact& c, std::int32_t q_vertex,
                                   const std::vector<Contact>& contacts, const ContactLookup& lookup,
                                   const SurfaceHash& surface, SurfaceHash::QueryScratch& scratch, double margin_m,
                                   BorderSum& sum) {
  const std::int32_t qi = lookup[c.object][q_vertex];
  if (qi >= 0 && contacts[qi].other == c.other) return 0;  // both inside B: not a border edge
  std::uint64_t work = 0;
  const Body& A = world.bodies[c.object];
  const Body& B = world.bodies[c.other];
  const Vec3& p = A.x_m[c.vertex];
  const Vec3& q = A.x_m[q_vertex];
  double best_t = -1.0;
  Vec3 best_normal = Vec3::Zero();
  const Vec3 grow = Vec3::Constant(margin_m);
  const Vec3 edge_lo = p.cwiseMin(q), edge_hi = p.cwiseMax(q);
  // The boxes the table was hashed with are the boxes at these positions
  // when every triangle was hashed this step (a cycle within one step).
  const bool hashed_boxes = surface.boxes_at(world.step_index);
  surface.for_each_candidate(c.other, edge_lo - grow, edge_hi + grow, scratch, [&](std::int32_t tri) {
    work += work::kCandidate;
    // Most candidates of a bucket lie apart from the edge: rejected without
    // an orient3d, and charged as before. On the hashed box when it is this
    // step's (the same min and max of the same corners, so the same
    // decision as triangle_box_apart(), NaN included), without reading the
    // triangle or its corners.
    if (hashed_boxes) {
      const SurfaceHash::Box& box = surface.hashed_box(c.other, tri);
      if (boxes_apart(edge_lo, edge_hi, box.lo, box.hi)) return;
    }
    const Triangle& f = B.mesh->surface[tri];
    const Vec3 &a = B.x_m[f[0]], &b = B.x_m[f[1]], &cc = B.x_m[f[2]];
    if ((!hashed_boxes && triangle_box_apart(edge_lo, edge_hi, a, b, cc)) ||
        !segment_crosses_triangle_perturbed(p, q, a, b, cc))
      return;
    const double t = segment_plane_parameter(p, q, a, b, cc);
    if (t > best_t) {
      best_t = t;
      best_normal = (b - a).cross(cc - a).normalized();
    }
  });
  if (best_t < 0.0) return work;  // no crossing found through this edge
  const Vec3 x = p + best_t * (q - p);
  const double dist2 = (x - p).squaredNorm();
  const double w = 1.0 / dist2;
  if (!std::isfinite(w)) {
    sum.coincident = true;
    sum.coincident_normals += best_normal;
    return work;
  }
  sum.w += w;
  sum.wd += w * (x - p).dot(best_normal);
  sum.wn += w * best_normal;
  return work;
}

void finish_border_depth(Contact& c, const BorderSum& sum) {
  if (sum.coincident && sum.coincident_normals.squaredNorm() > 0.0) {
    c.depth_m = 0.0;
    c.direction = sum.coincident_normals.normalized();
  } else if (sum.w > 0.0 && sum.wn.squaredNorm() > 0.0) {
    c.depth_m = sum.wd / sum.w;
    c.direction = sum.wn.normalized();
  } else {
    return;  // no crossing, or normals that cancel: no border depth
  }
  c.depth_source = DepthSource::Border;
  c.layer = 0;
}

std::uint64_t border_point_depth(const World& world, Contact& c, const std::vector<Contact>& contacts,
                                 const ContactLookup& lookup, const SurfaceHash& surface,
                                 SurfaceHash::QueryScratch& scratch, double margin_m) {
  std::uint64_t work = work::kBorderPoint;
  BorderSum sum;
  const auto& adjacency = world.bodies[c.object].mesh->vertex_neighbours;
  for (const std::int32_t* q = adjacency.begin(c.vertex); q != adjacency.end(c.vertex); ++q)
    work += border_edge_crossing(world, c, *q, contacts, lookup, surface, scratch, margin_m, sum);
  finish_border_depth(c, sum);
  return work;
}

std::uint64_t propagate_depth(const World& world, Contact& c, const std::vector<Contact>& contacts,
                              const ContactLookup& lookup, std::int32_t layer) {
  std::uint64_t work = work::kPropagation;
  const Body& A = world.bodies[c.object];
  const Vec3& p = A.x_m[c.vertex];
  double sum_mu = 0.0, sum_mu_d = 0.0;
  Vec3 sum_mu_r = Vec3::Zero();
  for (const std::int32_t* j = A.mesh->vertex_neighbours.begin(c.vertex); j != A.mesh->vertex_neighbours.end(c.vertex);
       ++j) {
    work += work::kNeighbour;
    const std::int32_t ci = lookup[c.object][*j];
    if (ci < 0) continue;
    const Contact& n = contacts[ci];
    if (n.other != c.other || n.depth_source == DepthSource::None || n.layer >= layer) continue;
    const Vec3 offset = A.x_m[*j] - p;
    const double mu = 1.0 / offset.squaredNorm();
    if (!std::isfinite(mu)) continue;  // coincident vertices: no direction to weigh
    sum_mu += mu;
    sum_mu_d += mu * (offset.dot(n.direction) + n.depth_m);
    sum_mu_r += mu * n.direction;
  }
  if (!(sum_mu > 0.0) || !(sum_mu_r.squaredNorm() > 0.0)) return work;
  c.depth_m = sum_mu_d / sum_mu;
  c.direction = sum_mu_r.normalized();
  c.depth_source = DepthSource::Propagated;
  c.layer = layer;
  return work;
}

}  // namespace tcb
