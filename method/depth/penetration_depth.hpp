#pragma once
/// Consistent penetration depth (Heidelberger, Teschner, Keiser, Mueller,
/// Gross, "Consistent Penetration Depth Estimation for Deformable Collision
/// Response", VMV 2004), as in METHOD.md s.3, in three resumable tasks:
///
/// - SurfaceHash::hash_triangle(): one surface triangle of a body that some
///   point collides with, at its current positions.
/// - border_point_depth(): for one colliding point p (of A, inside B), every
///   border edge (p, q) with q not colliding with B is intersected with B's
///   surface triangles found through the surface hash (exact perturbed test,
///   so an edge through a surface vertex or along a surface edge meets exactly
///   one triangle); of several crossings the one farthest from p is kept. With
///   crossings x_i, face normals n_i and w_i = 1/|x_i - p|^2:
///     d = sum w_i (x_i - p).n_i / sum w_i,   r = normalize(sum w_i n_i).
///   A crossing exactly at p (p on B's surface, as in the face-on-face plate
///   stack) has infinite weight: then d = 0 and r is the mean of those normals.
/// - propagate_depth(): for a colliding point with no depth, from neighbours
///   p_j with a depth from an earlier layer, mu_j = 1/|p_j - p|^2:
///     r = normalize(sum mu_j r_j),   d = sum mu_j ((p_j - p).r_j + d_j) / sum mu_j.
/// Normals are the triangles' face normals (not interpolated vertex normals).
/// A colliding point that no border path reaches (e.g. an object wholly inside
/// another) keeps DepthSource::None: it gets no depth-based force and is
/// counted by the caller (StepReport::depth_fallback).
/// Units: metres; depth positive inside B.

#include <limits>

#include "method/detection/spatial_hash.hpp"
#include "method/handler/contact.hpp"
#include "sim/world/world.hpp"

namespace tcb {

/// For each body, the index of each vertex's contact in the contact list (-1: none).
using ContactLookup = std::vector<std::vector<std::int32_t>>;

class SurfaceHash {
 public:
  SurfaceHash(const World& world, double cell_size_m, HashFunction hash);
  void begin_epoch() {
    m_hash.begin_epoch();
    m_boxes_step = kNoStep;
    m_ids_ascending = true;
    m_last_id = 0;
  }
  /// Hashes one surface triangle at the current positions; returns work units.
  std::uint64_t hash_triangle(const World& world, std::int32_t body, std::int32_t triangle);
  /// The work hash_triangle() would return for the triangle now, hashing
  /// nothing (a double: an absurd box neither overflows nor throws here).
  double triangle_work(const World& world, std::int32_t body, std::int32_t triangle) const;
  /// hash_triangle() for every triangle of `bodies` in order (each body's
  /// ascending), then build(), on the pool's threads: exactly the table those
  /// serial calls make (SpatialHash::insert_all_and_build). Call it right
  /// after begin_epoch(). work[i] receives the i-th triangle's work units.
  void hash_all(const World& world, const std::vector<std::int32_t>& bodies, WorkerPool& pool,
                std::vector<std::uint64_t>& work);
  /// The work hash_all() would charge for `bodies` now (summed on the pool;
  /// exact: integers below 2^53), hashing nothing.
  double work_of_all(const World& world, const std::vector<std::int32_t>& bodies, WorkerPool& pool) const;
  /// The triangles of `bodies` (the walk's length): each costs at least one unit.
  static std::size_t triangle_count(const World& world, const std::vector<std::int32_t>& bodies);
  /// After the last triangle: makes the hash queryable.
  void build() { m_hash.build(); }
  /// build() in pieces (SpatialHash::begin_build, build_some).
  void begin_build() { m_hash.begin_build(); }
  bool build_some(std::size_t max_visits) { return m_hash.build_some(max_visits); }

  /// Per-query "met" stamps over every triangle: one per thread that queries
  /// concurrently (a built, unchanging hash may be queried from many threads).
  /// Aligned to a cache line: each query bumps `query`, and the scratches
  /// of two threads side by side in one line would pass it back and forth.
  struct alignas(64) QueryScratch {
    std::vector<std::uint64_t> seen;
    std::uint64_t query = 0;
  };
  QueryScratch make_scratch() const { return QueryScratch{std::vector<std::uint64_t>(m_boxes.size(), 0), 0}; }
  /// Heap bytes of the table, the bodies' offsets and the hashed boxes (48
  /// bytes a triangle; not the scratches).
  std::size_t memory_bytes() const;

  /// A triangle's box as hashed: the min and max of its corners (in corner
  /// order, as triangle_box_apart() takes them) at the positions of the
  /// step that hashed it.
  struct Box {
    Vec3 lo, hi;
  };
  /// Whether every triangle of this epoch was hashed at the positions of
  /// world step `step_index` (so hashed_box() is the box at that step's
  /// positions); false once triangles of two steps are in (fine tasks
  /// spanning steps), and before the first.
  bool boxes_at(std::int64_t step_index) const { return m_boxes_step == step_index; }
  /// Whether this epoch's triangles went in by ascending id (the cycle's
  /// order), which lets a query skip the other bodies' runs of a bucket.
  bool ids_ascending() const { return m_ids_ascending; }
  /// The box a triangle of `body` was hashed with (one hashed this epoch).
  const Box& hashed_box(std::int32_t body, std::int32_t triangle) const {
    return m_boxes[m_offset[static_cast<std::size_t>(body)] + static_cast<std::uint32_t>(triangle)];
  }

  /// Calls f(triangle) for each distinct triangle of `body` hashed in the
  /// cells of [lo, hi], in the order the cells' buckets list them.
  template <typename F>
  void for_each_candidate(std::int32_t body, const Vec3& lo, const Vec3& hi, QueryScratch& scratch, F&& f) const {
    // A triangle of `body` is an id in [first, end). The cycle inserts the
    // triangles in ascending id (bodies ascending, each body's triangles
    // ascending, by hash_triangle() or hash_all()), and a bucket keeps its
    // insertion order, so then a bucket lists its ids ascending: this
    // body's form one run. Lower ids are passed by one comparison each, and
    // the scan stops at the first higher one, whose entries and the rest
    // are not read (a bucket's entries are mostly other bodies' where
    // bodies touch). The same triangles in the same order as testing every
    // entry. An epoch hashed in another order tests every entry.
    const std::uint32_t first = m_offset[static_cast<std::size_t>(body)];
    const std::uint32_t end = m_offset[static_cast<std::size_t>(body) + 1];
    std::uint64_t* const seen = scratch.seen.data();
    const std::uint64_t query = ++scratch.query;
    const bool ascending = m_ids_ascending;
    m_hash.for_each_range_in_box(lo, hi, [&](const std::uint32_t* it, const std::uint32_t* last) {
      if (!ascending) {
        for (; it != last; ++it) {
          const std::uint32_t id = *it;
          if (id - first >= end - first || seen[id] == query) continue;
          seen[id] = query;
          f(static_cast<std::int32_t>(id - first));
        }
        return;
      }
      while (it != last && *it < first) ++it;
      for (; it != last && *it < end; ++it) {
        const std::uint32_t id = *it;
        if (seen[id] == query) continue;
        seen[id] = query;
        f(static_cast<std::int32_t>(id - first));
      }
    });
  }

 private:
  void triangle_box(const World& world, std::int32_t body, std::int32_t triangle, Vec3& lo, Vec3& hi) const;
  /// Records that triangle `id` is inserted next (ids_ascending()).
  void note_insert(std::uint32_t id) {
    if (id < m_last_id) m_ids_ascending = false;
    m_last_id = id;
  }
  /// Records that a triangle was hashed at world step `step_index`.
  void note_hash_step(std::int64_t step_index) {
    if (m_boxes_step == kNoStep)
      m_boxes_step = step_index;
    else if (m_boxes_step != step_index)
      m_boxes_step = kMixedSteps;
  }
  static constexpr std::int64_t kNoStep = std::numeric_limits<std::int64_t>::min();
  static constexpr std::int64_t kMixedSteps = kNoStep + 1;
  /// first[k]: the walk index of bodies[k]'s first triangle; first.back() the walk's length.
  static std::vector<std::size_t> walk_starts(const World& world, const std::vector<std::int32_t>& bodies);
  /// The k with first[k] <= i < first[k + 1].
  static std::size_t body_at(const std::vector<std::size_t>& first, std::size_t i);
  SpatialHash m_hash;
  /// Per body, the id of its first triangle; one more entry, the total.
  std::vector<std::uint32_t> m_offset;
  /// Each triangle's box as hashed, by id (its body's offset + index): the
  /// border-edge search rejects most candidates on it, one read in place of
  /// the triangle's corners (4 scattered reads), when boxes_at() the step.
  std::vector<Box> m_boxes;
  std::int64_t m_boxes_step = kNoStep;
  /// Whether this epoch's triangles were inserted in non-decreasing id, so
  /// every bucket lists its ids so (for_each_candidate); the last inserted.
  bool m_ids_ascending = true;
  std::uint32_t m_last_id = 0;
};

/// border_point_depth() in pieces, one border edge a piece, for schedules
/// that split it (collision_cycle.hpp, fine tasks): a BorderSum starts empty,
/// border_edge_crossing() adds edge (p, q_vertex) when it is a border edge
/// that crosses B's surface (returns its work units: one a candidate
/// triangle; 0 when it is not a border edge), and finish_border_depth() sets
/// the contact's depth from the sums. Taken over p's neighbours in adjacency
/// order, with the same positions, this is border_point_depth() bit for bit
/// (less its work::kBorderPoint).
struct BorderSum {
  double w = 0.0, wd = 0.0;
  Vec3 wn = Vec3::Zero(), coincident_normals = Vec3::Zero();
  bool coincident = false;
};
std::uint64_t border_edge_crossing(const World& world, const Contact& contact, std::int32_t q_vertex,
                                   const std::vector<Contact>& contacts, const ContactLookup& lookup,
                                   const SurfaceHash& surface, SurfaceHash::QueryScratch& scratch, double margin_m,
                                   BorderSum& sum);
void finish_border_depth(Contact& contact, const BorderSum& sum);

/// Border-point depth of one contact (see file comment). Sets depth,
/// direction, source Border and layer 0 when p has a border edge that crosses
/// B's surface; leaves the contact without depth otherwise. Returns work units.
/// `margin_m` > 0: the surface triangles may have moved up to that far since
/// they were hashed; each edge's candidate box is grown by it (the exact
/// crossing test uses the current positions). 0: the paper's search.
/// Candidates whose box lies apart from the edge's are rejected (and
/// charged) before any orient3d: on the box the table hashed when every
/// triangle was hashed in this world step (SurfaceHash::boxes_at), else on
/// the corners' current positions; the same min and max, so the same answer.
/// This rests on what the whole cycle assumes (detected_step, batches):
/// positions change only in World::step, which advances step_index.
/// It writes only `contact` and reads of the other contacts only their
/// `other` (through the lookup), so with the contact list unchanged it may run
/// for several contacts concurrently, each thread with its own scratch.
std::uint64_t border_point_depth(const World& world, Contact& contact, const std::vector<Contact>& contacts,
                                 const ContactLookup& lookup, const SurfaceHash& surface,
                                 SurfaceHash::QueryScratch& scratch, double margin_m = 0.0);

/// Propagated depth of one contact at `layer` >= 1 from neighbours whose depth
/// comes from layers below it. Returns work units.
std::uint64_t propagate_depth(const World& world, Contact& contact, const std::vector<Contact>& contacts,
                              const ContactLookup& lookup, std::int32_t layer);

}  // namespace tcb
