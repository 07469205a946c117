#include "method/detection/tet_hash_detection.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>

#include "method/detection/morton_order.hpp"
#include "method/geometry/perturbed_predicates.hpp"
#include "method/handler/heap_bytes.hpp"
#include "method/handler/work_units.hpp"

namespace tcb {
namespace {

bool incident(const Tet& t, std::int32_t v) { return t[0] == v || t[1] == v || t[2] == v || t[3] == v; }

// Whether p lies outside the box [lo - grow, hi + grow]: the query's box
// test, the same comparisons of the same differences as the Eigen array form
// it replaced (p < lo - grow or p > hi + grow in any coordinate; a NaN never
// compares, so a NaN margin rejects nothing, as before). Written per
// coordinate because the query runs it for every entry of a bucket: under
// AddressSanitizer the array form's temporaries, poisoned and cleared on
// every call, took most of the detection tests' time (the test of every
// point against a one-bucket table: 129 s with the array form, 55 s so).
bool outside_grown_box(const Vec3& p, const Vec3& lo, const Vec3& hi, const Vec3& grow) {
  return p.x() < lo.x() - grow.x() || p.y() < lo.y() - grow.y() || p.z() < lo.z() - grow.z() ||
         p.x() > hi.x() + grow.x() || p.y() > hi.y() + grow.y() || p.z() > hi.z() + grow.z();
}

void tet_box(const Body& body, const Tet& tet, Vec3& lo, Vec3& hi) {
  // In locals, stored once: through the references the compiler must assume
  // lo and hi may alias the positions, and stored and reloaded both after
  // every vertex (perf: 15 % of micro_peer_inside's BM_OursKeptTable). The
  // same box, bit for bit: cwiseMin/Max keep the first of equal values, so
  // either order picks the earliest vertex holding the extreme.
  const Vec3* x = body.x_m.data();
  const Vec3 &a = x[tet[0]], &b = x[tet[1]], &c = x[tet[2]], &d = x[tet[3]];
  const Vec3 box_lo = a.cwiseMin(b).cwiseMin(c.cwiseMin(d));
  const Vec3 box_hi = a.cwiseMax(b).cwiseMax(c.cwiseMax(d));
  lo = box_lo;
  hi = box_hi;
}

// Whether a body's positions can change after the hash: a fixed passive body
// never moves, so refreshing its tets would find nothing.
bool can_move(const Body& body) { return !body.passive || body.trajectory || body.latent; }

// Whether the tet walks (serial, parallel, refresh) visit body b's tets: a
// body with a collision partner and, for a refresh, one that can move. One
// rule for every path, so their tables, overflows and work cannot drift.
bool walked(const World& world, const CollisionPairs& pairs, std::size_t b, bool movable_only) {
  return pairs.has_partner(b) && (!movable_only || can_move(world.bodies[b]));
}

// Each thread's body unions while a parallel pass stores boxes: one block a
// thread, blocks two unions (112 bytes) apart so no cache line holds two
// threads' unions (each tet's box may update one).
class PartUnions {
 public:
  PartUnions(int parts, std::size_t bodies) : m_stride(bodies + 2), m_unions(static_cast<std::size_t>(parts) * m_stride) {}
  BoxUnion& at(int part, std::size_t body) { return m_unions[static_cast<std::size_t>(part) * m_stride + body]; }
  /// The union over all threads of body b's boxes.
  BoxUnion merged(std::size_t body) const {
    BoxUnion all;
    for (std::size_t i = body; i < m_unions.size(); i += m_stride) all.add_union(m_unions[i]);
    return all;
  }

 private:
  std::size_t m_stride;
  std::vector<BoxUnion> m_unions;
};

// For each body b, the union of `boxes` over the walked bodies other than
// b: the walked bodies after b (suffix) and before b (prefix), two passes,
// not one a pair.
std::vector<BoxUnion> unions_of_others(const World& world, const CollisionPairs& pairs,
                                       const std::vector<BoxUnion>& boxes) {
  const std::size_t n = world.bodies.size();
  std::vector<BoxUnion> after(n + 1), others(n);
  for (std::size_t b = n; b-- > 0;) {
    after[b] = after[b + 1];
    if (walked(world, pairs, b, false)) after[b].add_union(boxes[b]);
  }
  BoxUnion before;
  for (std::size_t b = 0; b < n; ++b) {
    others[b] = before;
    others[b].add_union(after[b + 1]);
    if (walked(world, pairs, b, false)) before.add_union(boxes[b]);
  }
  return others;
}

Contact make_contact(const World& world, std::int32_t object, std::int32_t vertex, std::int32_t other,
                     std::int32_t tet) {
  const auto& x = world.bodies[other].x_m;
  const Tet& t = world.bodies[other].mesh->tets[tet];
  Contact c;
  c.object = object;
  c.vertex = vertex;
  c.other = other;
  c.tet = tet;
  c.barycentric = barycentric_weights(world.bodies[object].x_m[vertex], x[t[0]], x[t[1]], x[t[2]], x[t[3]]);
  c.detected_step = world.step_index;
  return c;
}

}  // namespace

TetHashDetector::TetHashDetector(const World& world, const DetectionSettings& settings) {
  std::uint32_t total = 0, vertices = 0;
  for (std::size_t b = 0; b < world.bodies.size(); ++b) {
    const TetMesh& mesh = *world.bodies[b].mesh;
    m_body_tet_offset.push_back(total);
    m_body_vertex_offset.push_back(vertices);
    vertices += static_cast<std::uint32_t>(mesh.positions_m.size());
    std::vector<char> in_tet(mesh.positions_m.size(), 0);
    for (std::size_t t = 0; t < mesh.tet_count(); ++t)
      if (!mesh.is_degenerate[t])
        for (const std::int32_t v : mesh.tets[t]) in_tet[static_cast<std::size_t>(v)] = 1;
    m_vertices_in_tets.push_back(std::all_of(in_tet.begin(), in_tet.end(), [](char c) { return c != 0; }) ? 1 : 0);
    m_owner.insert(m_owner.end(), mesh.tet_count(), static_cast<std::int32_t>(b));
    // The body's slots: its tets along a Morton curve of its rest positions
    // (so the same for every body sharing a mesh, whatever the world's state).
    std::vector<std::uint32_t> order(mesh.tet_count());
    if (settings.curve_order)
      order = morton_tet_order(mesh.positions_m, mesh.tets);
    else
      std::iota(order.begin(), order.end(), 0u);
    for (const std::uint32_t t : order) {
      m_file_id.push_back(total + t);
      m_slot_tets.push_back(mesh.tets[t]);
      m_slot_degenerate.push_back(mesh.is_degenerate[t]);
    }
    total += static_cast<std::uint32_t>(mesh.tet_count());
  }
  m_body_tet_offset.push_back(total);
  m_body_vertex_offset.push_back(vertices);
  m_slot_of.resize(total);
  for (std::uint32_t slot = 0; slot < total; ++slot) m_slot_of[m_file_id[slot]] = slot;
  m_boxes.resize(total, TetBox{Vec3::Zero(), Vec3::Zero()});
  m_body_boxes.resize(world.bodies.size());
  m_partner_boxes.resize(world.bodies.size());
  m_scratch = make_scratch();
  const std::size_t table = settings.table_size ? settings.table_size : next_prime(2 * std::size_t(total) + 1);
  m_hash = SpatialHash(settings.cell_size_m, table, settings.hash);
}

std::size_t TetHashDetector::memory_bytes() const {
  std::size_t bytes = m_hash.memory_bytes() + m_overflow.memory_bytes() + heap_bytes(m_hashed_cells) +
                      heap_bytes(m_part_left) + heap_bytes(m_left_ids) + heap_bytes(m_body_tet_offset) +
                      heap_bytes(m_owner) + heap_bytes(m_file_id) + heap_bytes(m_slot_tets) +
                      heap_bytes(m_slot_degenerate) + heap_bytes(m_slot_of) + heap_bytes(m_boxes) +
                      heap_bytes(m_body_boxes) + heap_bytes(m_partner_boxes) + heap_bytes(m_query_reach) +
                      heap_bytes(m_cell_tag) + heap_bytes(m_tagged_cells) + heap_bytes(m_own_tag) +
                      heap_bytes(m_body_vertex_offset) + heap_bytes(m_vertex_cell) + heap_bytes(m_reach_cells) +
                      heap_bytes(m_ask_untagged) + heap_bytes(m_vertices_in_tets) +
                      heap_bytes(m_scratch.tested) + heap_bytes(m_scratch.candidates);
  for (const LeftIds& left : m_part_left) bytes += heap_bytes(left.ids);
  return bytes;
}

void TetHashDetector::store_box(const Body& body, std::uint32_t id) {
  tet_box(body, m_slot_tets[id], m_boxes[id].lo, m_boxes[id].hi);
}

void TetHashDetector::record_hashed_cells(std::uint32_t id) {
  if (m_hashed_cells.empty()) return;
  CellLimits& cells = m_hashed_cells[id];
  for (int a = 0; a < 3; ++a) {
    // Cell indices are within +-2^50: exact as doubles, and so is the + 1.
    cells.lo[a] = static_cast<double>(m_hash.cell_of(m_boxes[id].lo[a]));
    cells.hi[a] = static_cast<double>(m_hash.cell_of(m_boxes[id].hi[a])) + 1.0;
  }
}

void TetHashDetector::check_world(const World& world) const {
  if (world.bodies.size() + 1 != m_body_vertex_offset.size())
    throw std::invalid_argument("TetHashDetector: made for " + std::to_string(m_body_vertex_offset.size() - 1) +
                                " bodies, given a world of " + std::to_string(world.bodies.size()));
  for (std::size_t b = 0; b < world.bodies.size(); ++b) {
    const std::size_t vertices = m_body_vertex_offset[b + 1] - m_body_vertex_offset[b];
    if (world.bodies[b].x_m.size() != vertices)
      throw std::invalid_argument("TetHashDetector: body " + std::to_string(b) + " has " +
                                  std::to_string(world.bodies[b].x_m.size()) + " positions, its mesh " +
                                  std::to_string(vertices) + " vertices");
    // The walks count a body's tets from its mesh and find their slots in
    // the detector's layout: another mesh's count would reach past it.
    const std::size_t tets = m_body_tet_offset[b + 1] - m_body_tet_offset[b];
    if (world.bodies[b].mesh->tet_count() != tets)
      throw std::invalid_argument("TetHashDetector: body " + std::to_string(b) + " has a mesh of " +
                                  std::to_string(world.bodies[b].mesh->tet_count()) + " tets, made for " +
                                  std::to_string(tets));
  }
}

std::uint64_t TetHashDetector::hash_tets(const World& world, const CollisionPairs& pairs, WorkerPool* pool,
                                         bool queries_at_these_positions) {
  check_world(world);
  begin_hash();
  // The box around every vertex that may query a body's tets (the vertices
  // of its partners), when the table serves these positions only; a body
  // with self-collision, or without that promise, has none (nothing skipped).
  const bool skip = queries_at_these_positions && m_hashed_cells.empty();
  // A dense grid over the walked bodies' vertices (which hold every stored
  // box) where only single-cell queries of this table are made.
  const bool dense = m_hashed_cells.empty() && !m_widening;
  std::vector<BoxUnion> vertices(world.bodies.size());
  if (skip || dense) {
    BoxUnion all;
    for (std::size_t o = 0; o < vertices.size(); ++o)
      if (walked(world, pairs, o, false)) {
        for (const Vec3& p : world.bodies[o].x_m) vertices[o].add_box(p, p);
        all.add_union(vertices[o]);
      }
    if (skip) reach_of_queries(world, pairs, vertices);
    // (Not with a NaN or infinite coordinate: min and max may pass over a
    // NaN, the probe does not. The hash then meets it as it always has.)
    if (dense && std::isfinite(all.probe))
      m_hash.begin_epoch_dense(all.lo, all.hi,
                               std::min(kDenseCellsPerBucket * m_hash.table_size(), kDenseCellsPerTet * m_boxes.size()));
  }
  // Without a pool the owners' build runs on this thread: its random accesses
  // stay in a core's cache, where insert_box() and build() reach across the
  // whole table for every entry (spatial_hash.hpp).
  std::optional<WorkerPool> caller;  // made only when needed: a pool is not free to build
  WorkerPool& threads = pool ? *pool : caller.emplace(1);
  // Slots run body by body, as the serial walk does (within a body, the
  // walk takes the file's order, this the slots': the same boxes, unions,
  // work and table contents, only a bucket's order within a body differs,
  // which no query sees).
  PartUnions part_boxes(threads.threads(), world.bodies.size());
  // Cells charged for tets not entered, and the tets left out before their
  // boxes were made, a thread's counts a cache line apart.
  struct alignas(64) SkippedCells {
    std::size_t cells = 0;
    std::size_t unmade = 0;
  };
  std::vector<SkippedCells> skipped(static_cast<std::size_t>(threads.threads()));
  // Within the tets entered, their cells no query point lies in (dense
  // grid only: its cells are its buckets, so a tag is exact).
  const bool tagged = skip && m_hash.dense() && tag_query_cells(world, pairs);
  m_told_apart = tagged;
  // A body's union of tet boxes taken from its vertices' where every vertex
  // is in a non-degenerate tet and the grid is dense, so every coordinate
  // finite: the same lo and hi (min and max are exact), and no tet then
  // updates a union. Only `probe` may differ, where a sum of huge
  // coordinates overflows to infinities of both signs, so either union may
  // be poisoned where the other is not, and reject no query where the
  // other rejects some; but a point either rejects lies outside every tet
  // box the union covers, so its query (unwidened, on a dense grid) finds
  // nothing and is charged its one unit either way (BoxUnion's contract).
  std::vector<char> union_of_vertices(world.bodies.size(), 0);
  for (std::size_t b = 0; b < world.bodies.size(); ++b)
    union_of_vertices[b] = m_hash.dense() && m_vertices_in_tets[b] && walked(world, pairs, b, false);
  const auto box_of = [&](int part, std::size_t id, Vec3& lo, Vec3& hi, std::uint32_t& item) {
    const auto b = static_cast<std::size_t>(m_owner[id]);
    const Body& body = world.bodies[b];
    if (!walked(world, pairs, b, false) || m_slot_degenerate[id]) return false;
    item = static_cast<std::uint32_t>(id);
    // A tet that no cell of its box would take is recognised from its
    // vertices' cells and left out before its box is made (its body's union
    // comes from the vertices, and no query reads the box of a tet not
    // entered). On
    // the dog pair that is 88 % of the tets; its tet hash took 2.06-2.18 ms
    // a step against 2.70-2.78 ms without (micro_collision_cycle
    // BM_DogPair/0/100/1, ms_hash_tets, alternated rounds).
    if (tagged && union_of_vertices[b] && m_ask_untagged[b]) {
      const std::size_t untaken = cells_if_none_takes(item, b);
      if (untaken > 0) {
        skipped[static_cast<std::size_t>(part)].cells += untaken;
        ++skipped[static_cast<std::size_t>(part)].unmade;
        return false;
      }
    }
    store_box(body, item);
    record_hashed_cells(item);
    lo = m_boxes[id].lo;
    hi = m_boxes[id].hi;
    if (!union_of_vertices[b]) part_boxes.at(part, b).add_box(lo, hi);
    if (skip && m_query_reach[b].misses(lo, hi)) {
      skipped[static_cast<std::size_t>(part)].cells += m_hash.cells_visited(lo, hi);  // throws as the insert would
      return false;
    }
    return true;
  };
  std::size_t cells = 0;
  if (tagged) {
    const std::uint32_t* const tag = m_cell_tag.data();
    const std::uint32_t* const own = m_own_tag.data();
    const std::int32_t* const owner = m_owner.data();
    cells = m_hash.insert_all_and_build(m_boxes.size(), box_of, threads, SpatialHash::kBucketsPerOwner, nullptr,
                                        [=](std::uint32_t id) {
                                          const std::uint32_t mine = own[owner[id]];
                                          return [tag, mine](std::uint32_t cell) { return takes(tag[cell], mine); };
                                        });
  } else {
    cells = m_hash.insert_all_and_build(m_boxes.size(), box_of, threads);
  }
  for (const SkippedCells& s : skipped) {
    cells += s.cells;
    m_tets_unmade += s.unmade;
  }
  for (std::size_t b = 0; b < world.bodies.size(); ++b)
    m_body_boxes[b] = union_of_vertices[b] ? vertices[b] : part_boxes.merged(b);
  finish_body_boxes(world, pairs);
  m_hash_body = world.bodies.size();
  return work::kCellInsert * cells;
}

std::size_t TetHashDetector::cells_if_none_takes(std::uint32_t id, std::size_t body) const {
  const Tet& tet = m_slot_tets[id];
  const GridOffset* const cell = m_vertex_cell.data() + m_body_vertex_offset[body];
  const GridOffset &a = cell[tet[0]], &b = cell[tet[1]], &c = cell[tet[2]], &d = cell[tet[3]];
  const auto least = [](std::uint32_t p, std::uint32_t q, std::uint32_t r, std::uint32_t s) {
    return std::min(std::min(p, q), std::min(r, s));
  };
  const auto greatest = [](std::uint32_t p, std::uint32_t q, std::uint32_t r, std::uint32_t s) {
    return std::max(std::max(p, q), std::max(r, s));
  };
  const std::uint64_t i0 = least(a.i, b.i, c.i, d.i), i1 = greatest(a.i, b.i, c.i, d.i);
  const std::uint64_t j0 = least(a.j, b.j, c.j, d.j), j1 = greatest(a.j, b.j, c.j, d.j);
  const std::uint64_t k0 = least(a.k, b.k, c.k, d.k), k1 = greatest(a.k, b.k, c.k, d.k);
  // Within the grid, so at most its cells (below 2^32): no overflow.
  const std::uint64_t cells = (i1 - i0 + 1) * (j1 - j0 + 1) * (k1 - k0 + 1);
  if (cells > kMaxCellsPerBox) return 0;
  // A cell that takes the tet holds a vertex of another walked body (or,
  // with self-collision, any vertex: then the reach is the whole grid), so
  // lies in the cells of m_query_reach: a range apart from them is
  // decided without reading a tag.
  const GridOffsetRange& reach = m_reach_cells[body];
  if (i1 < reach.lo.i || i0 > reach.hi.i || j1 < reach.lo.j || j0 > reach.hi.j || k1 < reach.lo.k ||
      k0 > reach.hi.k)
    return static_cast<std::size_t>(cells);
  const std::uint32_t* const tag = m_cell_tag.data();
  const std::uint32_t mine = m_own_tag[body];
  const auto takes_tet = [mine](std::uint32_t t) { return takes(t, mine); };
  const auto row = [&](std::uint64_t i, std::uint64_t j) { return tag + m_tag_grid.index(i, j, 0); };
  bool taken = false;
  if (i1 - i0 <= 1 && j1 - j0 <= 1 && k1 - k0 <= 1) {
    // At most two cells along each axis (70 % of the dog pair's tets): the
    // eight corners are every cell (a cell read twice where a side has
    // one), read without loops. BM_Ours/0 took 3.87-4.00 ms in 8 runs with
    // the loops alone, 3.61-3.74 ms in 6 of 8 so (the other two 4.6-4.8 ms,
    // on a loaded host), before the reach test above was added.
    const std::uint32_t *const a0 = row(i0, j0), *const a1 = row(i0, j1), *const b0 = row(i1, j0),
                               *const b1 = row(i1, j1);
    taken = takes_tet(a0[k0]) | takes_tet(a0[k1]) | takes_tet(a1[k0]) | takes_tet(a1[k1]) | takes_tet(b0[k0]) |
            takes_tet(b0[k1]) | takes_tet(b1[k0]) | takes_tet(b1[k1]);
  } else {
    // Every cell read, no early exit: most tets meet no tag.
    for (std::uint64_t i = i0; i <= i1; ++i)
      for (std::uint64_t j = j0; j <= j1; ++j) {
        const std::uint32_t* const r = row(i, j);
        for (std::uint64_t k = k0; k <= k1; ++k) taken |= takes_tet(r[k]);
      }
  }
  return taken ? 0 : static_cast<std::size_t>(cells);
}

void TetHashDetector::reach_of_queries(const World& world, const CollisionPairs& pairs,
                                       const std::vector<BoxUnion>& vertices) {
  // Every body that queries b's tets has a partner, so is walked: the other
  // walked bodies' vertex boxes hold every query point (more than b's
  // enabled partners', which only skips fewer tets).
  m_query_reach = unions_of_others(world, pairs, vertices);
  for (std::size_t b = 0; b < vertices.size(); ++b)
    if (pairs.enabled(b, b))  // its own vertices query it too: poisoned, so misses() nothing
      m_query_reach[b].probe = std::numeric_limits<double>::quiet_NaN();
}

bool TetHashDetector::tag_query_cells(const World& world, const CollisionPairs& pairs) {
  // Only where some walked body does not collide with itself: a
  // self-colliding body's tets go into every cell holding any vertex, so
  // where all bodies collide with themselves the tags could leave out only
  // cells holding no vertex at all, and the tag pass is spent for little.
  // (The quarter rule below declines those too; this exit only spares the
  // pass. The evidence is weak: finger_curl's tet hash took 0.108 ms a step with
  // tags and 0.087 without in one paired run, but 0.083-0.084 with and
  // 0.083-0.112 without in three more.)
  bool pays = false;
  for (std::size_t o = 0; o < world.bodies.size(); ++o)
    pays = pays || (walked(world, pairs, o, false) && !pairs.enabled(o, o));
  if (!pays) return false;
  // Last hash's tags cleared cell by cell, not the whole array: a grid
  // over bodies far apart has many cells and few tagged (fast_sphere_torus:
  // clearing them all took its tet hash from 0.043 to 0.068 ms a step).
  for (const std::uint32_t cell : m_tagged_cells) m_cell_tag[cell] = kNoVertex;
  m_tagged_cells.clear();
  if (m_cell_tag.size() < m_hash.grid_cells()) m_cell_tag.resize(m_hash.grid_cells(), kNoVertex);
  m_own_tag.resize(world.bodies.size());
  m_tag_grid = m_hash.grid_shape();
  m_vertex_cell.resize(m_body_vertex_offset.back());
  m_reach_cells.resize(world.bodies.size());
  for (std::size_t o = 0; o < world.bodies.size(); ++o) {
    const auto body = static_cast<std::uint32_t>(o);
    m_own_tag[o] = pairs.enabled(o, o) ? kNeverTag : body;
    // The same bodies as reach_of_queries(): every body that queries has a
    // partner, so is walked.
    if (!walked(world, pairs, o, false)) continue;
    // A vertex whose cell lies outside the cells of the box around the
    // other walked bodies' vertices (m_query_reach; poisoned with
    // self-collision) is in no cell of their tets' boxes, and no other
    // body's vertex shares its cell: untagged, its cell refuses what its
    // tag would (its own body's tets). So it is not tagged: bodies apart
    // tag few cells. Compared as cell indices (cell_of is monotone).
    const BoxUnion& reach = m_query_reach[o];
    const bool all = reach.poisoned();
    std::int64_t first[3], last[3];
    for (int a = 0; a < 3; ++a) {
      first[a] = m_hash.cell_of(reach.lo[a]);
      last[a] = m_hash.cell_of(reach.hi[a]);
    }
    // The same range as offsets into the grid (clamped to it: the grid
    // holds every walked vertex, so every cell a tag can take), or the
    // whole grid where every cell may take the body's tets.
    std::uint32_t reach_lo[3], reach_hi[3];
    for (int a = 0; a < 3; ++a) {
      const auto count = static_cast<std::int64_t>(m_tag_grid.cells[a]);
      const auto offset = [&](std::int64_t c) {
        return static_cast<std::uint32_t>(std::clamp<std::int64_t>(c - m_tag_grid.first[a], 0, count - 1));
      };
      reach_lo[a] = all ? 0 : offset(first[a]);
      reach_hi[a] = all ? static_cast<std::uint32_t>(count - 1) : offset(last[a]);
    }
    m_reach_cells[o] = {{reach_lo[0], reach_lo[1], reach_lo[2]}, {reach_hi[0], reach_hi[1], reach_hi[2]}};
    const std::vector<Vec3>& x = world.bodies[o].x_m;
    GridOffset* const offsets = m_vertex_cell.data() + m_body_vertex_offset[o];
    for (std::size_t v = 0; v < x.size(); ++v) {
      const std::int64_t c[3] = {m_hash.cell_of(x[v].x()), m_hash.cell_of(x[v].y()), m_hash.cell_of(x[v].z())};
      const std::size_t cell = m_hash.grid_cell(c[0], c[1], c[2]);
      if (cell == SpatialHash::kOutsideGrid) return false;
      // In the grid, so each offset is below its count (below 2^32).
      offsets[v] = {static_cast<std::uint32_t>(c[0] - m_tag_grid.first[0]),
                    static_cast<std::uint32_t>(c[1] - m_tag_grid.first[1]),
                    static_cast<std::uint32_t>(c[2] - m_tag_grid.first[2])};
      if (!all && (c[0] < first[0] || c[0] > last[0] || c[1] < first[1] || c[1] > last[1] || c[2] < first[2] ||
                   c[2] > last[2]))
        continue;
      std::uint32_t& tag = m_cell_tag[cell];
      if (tag == kNoVertex) m_tagged_cells.push_back(static_cast<std::uint32_t>(cell));
      tag = tag == kNoVertex || tag == body ? body : kSeveralBodies;
    }
  }
  // Whether cells_if_none_takes() is worth asking for a body's tets: where
  // a quarter or more of its vertices lie in cells that take its tets,
  // most of its tets are taken too and the check is spent for nothing.
  // (The share of tets taken against the share of vertices in taking
  // cells, all bodies together, every 50th hash of a 120-step run: dog
  // pair 0.12 and 0.035, plates20 0.98-1.00 and 0.97-0.99, sneaker_grass
  // 0-0.21 and 0-0.09, two_blocks 0.33 and 0.25. Asked for every tet,
  // plates20's tet hash took 0.92-0.94 ms a step against 0.76-0.79 without
  // the check; with this rule 0.76-0.78: micro_collision_cycle
  // BM_Plates20/0/1, ms_hash_tets, alternated rounds.)
  m_ask_untagged.assign(world.bodies.size(), 0);
  bool some_asked = false;
  for (std::size_t o = 0; o < world.bodies.size(); ++o) {
    if (!walked(world, pairs, o, false)) continue;
    const GridOffset* const offsets = m_vertex_cell.data() + m_body_vertex_offset[o];
    const std::size_t n = world.bodies[o].x_m.size();
    std::size_t taking = 0;
    for (std::size_t v = 0; v < n; ++v) {
      const GridOffset& c = offsets[v];
      const std::uint32_t tag = m_cell_tag[m_tag_grid.index(c.i, c.j, c.k)];
      taking += takes(tag, m_own_tag[o]);
    }
    m_ask_untagged[o] = 4 * taking < n;
    some_asked = some_asked || m_ask_untagged[o];
  }
  // And the tags themselves only where some body is asked: where every
  // walked body has a quarter or more of its vertices in taking cells, the
  // tags leave few entries out and their checks cost more than the smaller
  // table saves. plates20 (BM_ThreadsPaired/1/0, a temporary switch, two
  // alternated rounds; a third without tags ran on a loaded host):
  // ms_hash_tets 0.74-0.81 ms on one thread and 0.89-0.92 ms on two with
  // the tags, 0.67-0.73 and 0.74-0.75 without; ms_query_points the same
  // (1.86-1.93 and 1.25-1.27 ms).
  return some_asked;
}

void TetHashDetector::begin_hash() {
  m_partner_boxes_ready = false;
  m_tets_unmade = 0;
  m_told_apart = false;
  // Every union empty until its body's tets are stored again: a body the
  // walk then skips (no partner) keeps an empty one.
  for (BoxUnion& u : m_body_boxes) u = BoxUnion{};
  m_hash.begin_epoch();
  m_hash_body = 0;
  m_hash_tet = 0;
  m_overflow_active = false;
  m_overflow_tets = 0;
}

void TetHashDetector::enable_refresh() {
  if (!m_hashed_cells.empty()) return;
  m_hashed_cells.assign(m_boxes.size(), CellLimits{});
  // The main table's size. A smaller overflow decides the same answers, but
  // not always the same work: a widened query (margin > 0) searches several
  // buckets and keeps one best-so-far across them, so a tet of a far cell
  // sharing a bucket searched early can be charged before the early stop
  // would have passed it by.
  m_overflow = SpatialHash(m_hash.cell_size_m(), m_hash.table_size(), m_hash.function());
}

void TetHashDetector::begin_refresh() {
  m_partner_boxes_ready = false;
  m_overflow.begin_epoch();
  m_overflow_active = false;
  m_overflow_tets = 0;
  m_hash_body = 0;
  m_hash_tet = 0;
}

template <typename Visit>
std::uint64_t TetHashDetector::walk_tets(const World& world, const CollisionPairs& pairs, bool movable_only,
                                         std::size_t max_tets, bool& done, Visit&& visit) {
  if (m_hash_body == 0 && m_hash_tet == 0) check_world(world);  // once a walk, not every piece
  std::uint64_t work = 0;
  std::size_t visited = 0;
  for (; m_hash_body < world.bodies.size(); ++m_hash_body, m_hash_tet = 0) {
    const Body& body = world.bodies[m_hash_body];
    if (!walked(world, pairs, m_hash_body, movable_only)) continue;
    const std::vector<char>& degenerate = body.mesh->is_degenerate;
    // A body's union starts afresh at its first tet: every tet of a walked
    // body gets its box stored again in this walk (none yet when the
    // cursor stands at 0, even when the walk resumes there).
    BoxUnion& union_box = m_body_boxes[m_hash_body];
    if (m_hash_tet == 0) union_box = BoxUnion{};
    for (; m_hash_tet < body.mesh->tet_count(); ++m_hash_tet) {
      if (visited == max_tets) {
        done = false;
        return work;
      }
      ++visited;
      const std::size_t t = m_hash_tet;
      if (degenerate[t]) continue;
      const std::uint32_t id = m_slot_of[m_body_tet_offset[m_hash_body] + static_cast<std::uint32_t>(t)];
      store_box(body, id);
      union_box.add_box(m_boxes[id].lo, m_boxes[id].hi);
      work += visit(id);
    }
  }
  done = true;
  finish_body_boxes(world, pairs);
  return work;
}

bool TetHashDetector::within_hashed_cells(std::uint32_t id) const {
  // cell_of(x) >= c iff grid_coordinate(x) >= c, and cell_of(x) <= c iff
  // grid_coordinate(x) < c + 1 (spatial_hash.hpp). Not short-circuited:
  // most tets stay in their cells, and then all six are needed anyway.
  const CellLimits& cells = m_hashed_cells[id];
  const TetBox& box = m_boxes[id];
  bool inside = true;
  for (int a = 0; a < 3; ++a)
    inside &= (m_hash.grid_coordinate(box.lo[a]) >= cells.lo[a]) & (m_hash.grid_coordinate(box.hi[a]) < cells.hi[a]);
  return inside;
}

std::uint64_t TetHashDetector::refresh_some_tets(const World& world, const CollisionPairs& pairs,
                                                 std::size_t max_tets, bool& done) {
  // The current box is stored either way: queries reject with it.
  const std::uint64_t work = walk_tets(world, pairs, true, max_tets, done, [&](std::uint32_t id) {
    if (within_hashed_cells(id)) return work::kTetBox;
    ++m_overflow_tets;
    return work::kTetBox + work::kCellInsert * m_overflow.insert_box(m_boxes[id].lo, m_boxes[id].hi, id);
  });
  if (done) m_overflow_active = m_overflow_tets > 0;
  return work;
}

std::uint64_t TetHashDetector::refresh_tets(const World& world, const CollisionPairs& pairs, WorkerPool* pool) {
  check_world(world);
  begin_refresh();  // from the first tet, whatever a refresh before left
  // walk_tets()'s choice of tets, by slot: slots run body by body, as the
  // walk does (within a body in another order, which nothing here sees).
  std::optional<WorkerPool> caller;  // made only when needed: a pool is not free to build
  WorkerPool& threads = pool ? *pool : caller.emplace(1);
  m_part_left.resize(static_cast<std::size_t>(threads.threads()));
  // Every list emptied here, not by its part: a part with an empty range
  // never runs.
  for (LeftIds& left : m_part_left) left.ids.clear();
  PartUnions part_boxes(threads.threads(), world.bodies.size());
  const auto check = [&](int part, std::size_t begin, std::size_t end) {
    std::uint64_t visited = 0;
    // The current body's union in registers, handed to part_boxes when the
    // body changes (slots run body by body), not a memory update a tet (which
    // measured 1.03-1.05 of this refresh's time, ms_hash_tets with
    // keep_table, 6 paired rounds).
    std::size_t body_of_union = world.bodies.size();
    BoxUnion union_box;
    std::vector<std::uint32_t>& left = m_part_left[static_cast<std::size_t>(part)].ids;
    for (std::size_t id = begin; id < end; ++id) {
      const std::size_t b = static_cast<std::size_t>(m_owner[id]);
      const Body& body = world.bodies[b];
      if (!walked(world, pairs, b, true) || m_slot_degenerate[id]) continue;
      store_box(body, static_cast<std::uint32_t>(id));
      if (b != body_of_union) {
        if (body_of_union < world.bodies.size()) part_boxes.at(part, body_of_union).add_union(union_box);
        body_of_union = b;
        union_box = BoxUnion{};
      }
      union_box.add_box(m_boxes[id].lo, m_boxes[id].hi);
      if (!within_hashed_cells(static_cast<std::uint32_t>(id))) left.push_back(static_cast<std::uint32_t>(id));
      ++visited;
    }
    if (body_of_union < world.bodies.size()) part_boxes.at(part, body_of_union).add_union(union_box);
    return visited;
  };
  std::vector<std::uint64_t> visited(static_cast<std::size_t>(threads.threads()), 0);
  threads.for_ranges(m_boxes.size(), [&](int part, std::size_t begin, std::size_t end) {
    visited[static_cast<std::size_t>(part)] = check(part, begin, end);
  });
  // The refreshed bodies' unions anew; the others' boxes were not touched.
  for (std::size_t b = 0; b < world.bodies.size(); ++b)
    if (walked(world, pairs, b, true)) m_body_boxes[b] = part_boxes.merged(b);
  std::uint64_t work = 0;
  for (const std::uint64_t v : visited) work += work::kTetBox * v;
  // The tets that left their cells into the overflow, in slot order, built
  // at once as hash_tets() builds the main table (its buckets list their
  // tets body by body, as queries need, and the table is the same on any
  // thread count); a later build is then a no-op. Parts hold ascending
  // ranges of slots, so their lists in part order are the slots in
  // ascending order.
  m_left_ids.clear();
  for (const LeftIds& left : m_part_left) m_left_ids.insert(m_left_ids.end(), left.ids.begin(), left.ids.end());
  m_overflow_tets = m_left_ids.size();
  const auto box_of = [&](std::size_t i, Vec3& lo, Vec3& hi, std::uint32_t& item) {
    item = m_left_ids[i];
    lo = m_boxes[item].lo;
    hi = m_boxes[item].hi;
    return true;
  };
  work += work::kCellInsert * m_overflow.insert_all_and_build(m_left_ids.size(), box_of, threads);
  finish_body_boxes(world, pairs);
  m_hash_body = world.bodies.size();
  m_overflow_active = m_overflow_tets > 0;
  return work;
}

void TetHashDetector::finish_body_boxes(const World& world, const CollisionPairs& pairs) {
  m_partner_boxes = unions_of_others(world, pairs, m_body_boxes);
  m_partner_boxes_ready = true;
}

std::uint64_t TetHashDetector::hash_some_tets(const World& world, const CollisionPairs& pairs, std::size_t max_tets,
                                              bool& done) {
  return walk_tets(world, pairs, false, max_tets, done, [&](std::uint32_t id) {
    const std::uint64_t work = work::kCellInsert * m_hash.insert_box(m_boxes[id].lo, m_boxes[id].hi, id);
    record_hashed_cells(id);
    return work;
  });
}

std::optional<Contact> TetHashDetector::query_point(const World& world, const CollisionPairs& pairs,
                                                    std::int32_t object, std::int32_t vertex, std::uint64_t& work,
                                                    double margin_m, QueryScratch& scratch) const {
  const Vec3& p = world.bodies[object].x_m[vertex];
  if (++scratch.query == 0) {  // wrapped: reset the per-tet stamps once
    std::fill(scratch.tested.begin(), scratch.tested.end(), 0);
    scratch.query = 1;
  }
  work += work::kPointQuery;
  // The querying body's own tets are one range of ids. Without
  // self-collision they are rejected by that range, before any memory is
  // read: most entries near a surface are the body's own.
  const std::uint32_t own_first = m_body_tet_offset[static_cast<std::size_t>(object)];
  const std::uint32_t own_count =
      pairs.enabled(object, object) ? 0 : m_body_tet_offset[static_cast<std::size_t>(object) + 1] - own_first;
  const Vec3 grow = Vec3::Constant(margin_m);
  if (!(margin_m <= 0.0) && m_hash.dense())
    throw std::logic_error("TetHashDetector: a widened query needs enable_widening() before the hash");
  // Outside every other hashed body's box union grown by the margin, each
  // tet of every bucket searched would fail its (grown) box test: no
  // contact, and the work of a query that searched its cells, counted
  // without reading them. Not with self-collision (the own body's tets are
  // not in the union); a NaN margin never rejects (BoxUnion::rejects).
  if (m_partner_boxes_ready && own_count > 0 &&
      m_partner_boxes[static_cast<std::size_t>(object)].rejects(p, margin_m)) {
    if (margin_m > 0.0) {
      work += work::kPointQuery * (m_hash.cells_visited(p - grow, p + grow) - 1);
      if (m_overflow_active) work += work::kPointQuery * m_overflow.cells_visited(p - grow, p + grow);
    } else if (m_overflow_active) {
      work += work::kPointQuery;
    }
    return std::nullopt;
  }
  // The smallest file id of a tet found holding p, and the end of its
  // body's range (ids and slots share the ranges): an entry at or past that
  // end is a tet of a later body, so of a larger file id.
  std::uint32_t best = UINT32_MAX;
  std::uint32_t best_body_end = UINT32_MAX;
  // A tet met twice is tested once. In one bucket its entries are adjacent
  // (insert_box() puts all of a tet's cells in at once, and a bucket keeps
  // insertion order), so a query of one cell in the main table alone skips a
  // repeat of the last slot without a stamp; a query over several
  // buckets, or the overflow table too, stamps each tet met.
  const bool one_bucket = !(margin_m > 0.0) && !m_overflow_active;
  std::uint32_t last = UINT32_MAX;
  std::vector<std::uint64_t>& candidates = scratch.candidates;
  // The file order's answer and charge (header: "Tet numbering"): a scan in
  // ascending file id skips (unread, unstamped) every entry at or above the
  // best so far, and stops at its first hit. So an entry at or above the
  // best is passed over here before any stamp; the bucket's candidates
  // (box test passed) are gathered, then sorted by file id and tested in
  // that order, each charged, up to the first hit: the exact tests and
  // charges of the file order (testing in slot order and charging those at
  // or below the best found measured 1.09x plates20's query stage: a hit
  // met late in slot order costs the exact tests the file order skips).
  // The entries' arrays as plain pointers (the lambdas would otherwise
  // reload them through `this` after every push_back), and the body of the
  // entries being scanned, its slot range and whether it is a partner,
  // looked up once per run of one body's entries (a bucket lists them body
  // by body, see below) instead of once per entry. The box test comes
  // before the file id and the stamps: every test here only rejects, and a
  // tet rejected by its box is rejected again wherever it is met, so the
  // candidates gathered are the same in any order.
  const std::int32_t* const owner = m_owner.data();
  const std::uint32_t* const file_id = m_file_id.data();
  const TetBox* const boxes = m_boxes.data();
  std::int32_t run_body = -1;
  std::uint32_t run_first = 0, run_count = 0;
  bool run_enabled = false;
  const auto gather = [&](std::uint32_t id) {
    if (id - run_first >= run_count) {
      run_body = owner[id];
      run_first = m_body_tet_offset[static_cast<std::size_t>(run_body)];
      run_count = m_body_tet_offset[static_cast<std::size_t>(run_body) + 1] - run_first;
      run_enabled = pairs.enabled(object, run_body);
    }
    if (!run_enabled) return;
    const TetBox& box = boxes[id];
    if (outside_grown_box(p, box.lo, box.hi, grow)) return;
    const std::uint32_t file = file_id[id];
    if (file >= best) return;
    if (one_bucket) {
      if (id == last) return;
      last = id;
    } else {
      if (scratch.tested[id] == scratch.query) return;
      scratch.tested[id] = scratch.query;
    }
    if (run_body == object && incident(m_slot_tets[id], vertex)) return;
    candidates.push_back(std::uint64_t(file) << 32 | id);
  };
  const auto test_candidates = [&] {
    if (candidates.size() > 1) std::sort(candidates.begin(), candidates.end());
    for (const std::uint64_t c : candidates) {
      const auto id = static_cast<std::uint32_t>(c);
      const std::size_t other = static_cast<std::size_t>(m_owner[id]);
      const Tet& tet = m_slot_tets[id];
      const auto& x = world.bodies[other].x_m;
      work += work::kCandidate;
      if (point_in_tet_perturbed(p, x[tet[0]], x[tet[1]], x[tet[2]], x[tet[3]])) {
        best = static_cast<std::uint32_t>(c >> 32);
        best_body_end = m_body_tet_offset[other + 1];
        return;
      }
    }
  };
  // A bucket lists its tets body by body in body order: every hashing path
  // inserts them so, and a bucket keeps insertion order (spatial_hash.hpp).
  // So the querying body's own tets, one range of slots, are one block,
  // stepped over by a binary search before any of their memory is read
  // (most entries near a surface are the body's own; the query stage on the
  // dog pair fell from 6.8 to 3.0 ms with it, where each was tested and
  // rejected; the range is partitioned by "below the block's end", all a
  // binary search needs); and once a tet holds p, no entry of a later body
  // can be a smaller file id, so the bucket is done. Both skip only entries
  // that are rejected unread and uncharged anyway.
  const std::uint32_t own_end = own_first + own_count;
  const auto scan = [&](const std::uint32_t* it, const std::uint32_t* end) {
    candidates.clear();
    while (it != end) {
      const std::uint32_t id = *it;
      if (id >= best_body_end) break;
      if (id - own_first < own_count) {
        it = std::lower_bound(it, end, own_end);
        continue;
      }
      gather(id);
      ++it;
    }
    test_candidates();
  };
  // Scans a table's buckets for p (the cells within the margin, or p's
  // cell); returns the cells searched.
  const auto search = [&](const SpatialHash& table) -> std::size_t {
    if (margin_m > 0.0) return table.for_each_range_in_box(p - grow, p + grow, scan);
    const SpatialHash::Entries entries = table.cell_entries(p);
    scan(entries.first, entries.last);
    return 1;
  };
  work += work::kPointQuery * (search(m_hash) - 1);  // the first cell is the query's own unit
  if (m_overflow_active) work += work::kPointQuery * search(m_overflow);  // a unit a cell of the overflow
  if (best == UINT32_MAX) return std::nullopt;
  const std::int32_t other = m_owner[best];  // a file id: the slots' ranges are the ids'
  return make_contact(world, object, vertex, other, static_cast<std::int32_t>(best - m_body_tet_offset[other]));
}

std::optional<Contact> brute_force_query_point(const World& world, const CollisionPairs& pairs, std::int32_t object,
                                               std::int32_t vertex, std::uint64_t& work) {
  const Vec3& p = world.bodies[object].x_m[vertex];
  work += work::kPointQuery;
  for (std::size_t b = 0; b < world.bodies.size(); ++b) {
    if (!pairs.enabled(object, b)) continue;
    const Body& B = world.bodies[b];
    const std::vector<char>& degenerate = B.mesh->is_degenerate;
    for (std::size_t t = 0; t < B.mesh->tet_count(); ++t) {
      const Tet& tet = B.mesh->tets[t];
      if (degenerate[t] || (b == static_cast<std::size_t>(object) && incident(tet, vertex))) continue;
      work += work::kCandidate;
      if (point_in_tet_perturbed(p, B.x_m[tet[0]], B.x_m[tet[1]], B.x_m[tet[2]], B.x_m[tet[3]]))
        return make_contact(world, object, vertex, static_cast<std::int32_t>(b), static_cast<std::int32_t>(t));
    }
  }
  return std::nullopt;
}

}  // namespace tcb
