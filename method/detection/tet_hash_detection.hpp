#pragma once
/// Point-in-tet detection through a spatial hash of the tets (Teschner et al.
/// 2003, in the paper's order, which makes one point query the atomic task):
///   1. hash_tets(): every non-degenerate tet of every body that has a
///      collision partner goes into all cells its AABB covers (the paper: one
///      task, not interruptible; the AABBs are kept for step 2; for a caller
///      that queries at once, unwidened, the tets no query point can reach
///      are charged but left out: see hash_tets(); unless widened or
///      refreshed queries may follow, the table is a dense grid over the
///      walked vertices' cells: see enable_widening()). Resumable in
///      pieces: begin_hash(), hash_some_tets() until done, then the table's
///      begin_build()/build_some() (hash()); the result is hash_tets()'s
///      whenever positions do not change in between. Tets hashed in an earlier
///      step keep that step's AABB, as the whole hash does in the paper's
///      schedule once the cycle spans steps;
///   1b. (settings rehash_stale and keep_table, ours) refresh: once the
///      table is older than the positions, begin_refresh() and
///      refresh_some_tets() (or refresh_tets(), all at once) revisit every
///      tet of a body that can move, store its current AABB, and enter into a
///      second table (the overflow) each tet whose current AABB
///      reaches a cell outside the cells it was hashed in (the overflow has
///      the main table's size but holds only those tets); build the overflow
///      (mutable_overflow()), then queries search both tables. After a
///      complete pass, with positions unchanged since, query_point() finds
///      exactly what a fresh hash_tets() would (brute_force_query_point()'s
///      points): a tet holding p covers p's cell with its current AABB, so it
///      is in the main table's bucket (cells unchanged) or the overflow's;
///   2. query_point(): first, without self-collision, the vertex against
///      the box around every other hashed body's tets (the union of their
///      stored boxes, kept by every hashing and refresh path, or on a dense
///      hash the box around their vertices, the same lo and hi), grown by the
///      margin of a widened query: outside it, every tet of every bucket
///      searched would fail its (grown) box test, so the query ends there
///      with the same answer (none) and work (a unit a cell searched, in
///      each table searched), without reading the table (half the dog
///      pair's vertices: 78 ns a query with the table, 7 without,
///      micro_peer_inside BM_QueryClasses/0/0; widened a quarter cell, 234
///      and 20 ns, BM_QueryClasses/0/25; both measured on the hash, before
///      the dense grid, which /0 now reads). A NaN margin never rejects.
///      Then the vertex is hashed; for each tet in its bucket:
///      skip pairs that are not enabled and tets incident to the vertex
///      (self-collision), reject by the stored AABB, then the exact perturbed
///      point-in-tet test (perturbed_predicates.hpp). The cheapest filters
///      first: a bucket lists its tets body by body, in body order (every
///      hashing path inserts body by body), so without self-collision the
///      querying body's own tets (one range of slots) are one block of it,
///      stepped over by a binary search before any of their memory is read
///      (most entries near a surface on the dog pair), and the bucket ends
///      at the first entry of a later body than a tet already holding the
///      point; then the owner, a dense 4-byte array that stays in cache;
///      testing the 48-byte box first measured 1.8x slower there.
/// A point inside several tets (overlapping objects or a folded mesh) is
/// reported in the one with the smallest (body, tet) index, the file's.
/// Work: work_units.hpp; a query is charged what a scan of its buckets in
/// ascending file index, stopping at its first hit, is charged (below).
///
/// Tet numbering. Inside the detector a tet has a slot: within its body's
/// range of global ids (the same ranges as the file's), the body's tets
/// ordered along a Morton curve of its rest positions (morton_order.hpp;
/// DetectionSettings::curve_order), so the tets of one bucket, and the tets
/// one after another in a walk, sit near each other in memory: the boxes,
/// stamps and vertex indices (copied into slot order) a query or a hash
/// reads. The file's numbering (a mesh's order; vertices keep it, measured
/// as poor: a tet's vertex indices span thousands) is what every answer,
/// contact and charge is defined in: buckets hold slots, so a bucket need
/// not list its tets in file order; a query therefore gathers a bucket's
/// candidates (box test passed, below its best so far in file order), then
/// tests and charges them in ascending file order up to the first hit:
/// what a scan of the bucket in file order, stopping at its first hit,
/// tests and is charged. So the answer, work and every stamp that matters
/// are those of the file order, whatever order a bucket lists its tets in
/// (the walk's or the slots'), which the work test checks against a
/// file-order count.

#include <optional>

#include "method/detection/box_union.hpp"
#include "method/detection/collision_pairs.hpp"
#include "method/detection/spatial_hash.hpp"
#include "method/handler/contact.hpp"

namespace tcb {

struct DetectionSettings {
  double cell_size_m = 0.0;     ///< > 0
  std::size_t table_size = 0;   ///< 0: next prime above twice the tet count
  HashFunction hash = HashFunction::Mixed;
  /// Number the tets inside the detector along a Morton curve of each
  /// body's rest positions (a layout only: every answer, contact and unit of
  /// work is the same either way; see "Tet numbering" above). false keeps
  /// the file's order, for measuring the layout side by side.
  bool curve_order = true;
};

class TetHashDetector {
 public:
  /// Every later call takes a world of the same bodies and meshes, each
  /// body with one position a mesh vertex: hashing a world whose body
  /// count, position counts or meshes' tet counts differ throws
  /// std::invalid_argument (its per-vertex and per-tet arrays are laid out
  /// for these meshes; a different mesh of the same counts is not detected).
  TetHashDetector(const World& world, const DetectionSettings& settings);

  /// Stage 1: hashes all tets at the current positions; returns work units.
  /// By SpatialHash::insert_all_and_build(), on the pool's threads or without
  /// one on the caller's: the same table, stored boxes, work units and errors
  /// on any thread count, and as begin_hash(), hash_some_tets() and a build
  /// (those always hash: where hash_tets() lays out a dense grid, only the
  /// buckets differ, not what any query finds or is charged).
  /// `queries_at_these_positions`: the caller promises that every query of
  /// this table is made before any position changes (a cycle run to its end
  /// in one call) and unwidened (margin_m <= 0). Then, unless refreshing is
  /// enabled (a refresh keeps the table for later positions), a tet whose
  /// box lies strictly apart from the box around every vertex of the bodies
  /// that may query it (every other walked body; no self-collision in its
  /// body) is not entered: no query point can pass its box test, so every
  /// query finds and is charged exactly what it would with the tet entered
  /// (a widened query could pass its grown box and be charged it: hence
  /// unwidened). Its cells are still charged (work units unchanged), its
  /// HashOverflow thrown as the insert would (the same cell count, checked),
  /// its box stored and in its body's union (but see below). In a dense
  /// grid, a tet entered goes only into the cells of its box where a vertex
  /// of another walked body lies (of any walked body, if its own collides
  /// with itself), where some walked body has under a quarter of its
  /// vertices in cells that would take its tets (so never where every
  /// walked body collides with itself; cells_told_apart()): a query
  /// searches its point's cell alone, and the tets of the point's own body
  /// it would skip unread and uncharged; all its cells are charged too.
  /// Only the table is smaller (memory_bytes() may be too). A tet that
  /// rule would enter into no cell may be recognised from its vertices'
  /// cells and left out before its box is made (cells_if_none_takes(),
  /// asked for a body whose every vertex lies in a non-degenerate tet and
  /// under a quarter of whose vertices lie in cells that take its tets):
  /// its box is then not stored (tets_unmade() counts them). On any dense
  /// grid, a body whose every vertex lies in a non-degenerate tet gets the
  /// box around its vertices as its union (the same lo and hi). The
  /// paper's algorithm with a pre-filter the design notes measured (skip
  /// tets outside the other object's box) and its refinement to cells (on
  /// the dog pair 300,007 entries become 31,251; micro_peer_inside's
  /// BM_PeersPaired/0, ours 6.5-7.1 ms to 4.3-4.5 ms, 6.0 once on a loaded
  /// host). Boxes left unmade: BM_Ours/0 3.82-4.04 ms to 3.22-3.32 ms (8
  /// alternated runs of each, a temporary switch, not committed).
  std::uint64_t hash_tets(const World& world, const CollisionPairs& pairs, WorkerPool* pool = nullptr,
                          bool queries_at_these_positions = false);
  /// Stage 1 in pieces: begin_hash() empties the table; each hash_some_tets()
  /// hashes the next `max_tets` tets (in hash_tets()'s order) at the current
  /// positions, returns their work units, and sets `done` after the last;
  /// then build the table (mutable_hash().begin_build(), build_some()).
  void begin_hash();
  std::uint64_t hash_some_tets(const World& world, const CollisionPairs& pairs, std::size_t max_tets, bool& done);
  SpatialHash& mutable_hash() { return m_hash; }
  /// Makes refreshing possible: from the next hash on, every tet's cells are
  /// kept (48 bytes a tet) and the overflow table is allocated.
  void enable_refresh();
  /// Makes widened queries (margin_m > 0) possible from the next hash on.
  /// Without this or enable_refresh(), hash_tets() lays the table out as a
  /// dense grid over the cells of the walked bodies' vertices where that
  /// range has at most kDenseCellsPerBucket cells a hash bucket and
  /// kDenseCellsPerTet a tet (spatial_hash.hpp; 12 bytes a cell, the
  /// buckets kept at their largest: at most 96 bytes a tet, and 32 more for
  /// the tags of hash_tets() skipping, 12 a vertex for their cells): a
  /// query of the point's cell then meets the tets that pass its box test in the hash's
  /// order (the same answers and work, cheaper to build and read), but a
  /// search over several cells, or over the main table and an overflow with
  /// one best-so-far, would meet them in another order than the hash and
  /// could be charged differently; so a widened query (margin_m > 0, or
  /// NaN) on a dense table throws std::logic_error.
  void enable_widening() { m_widening = true; }
  static constexpr std::size_t kDenseCellsPerBucket = 4;
  static constexpr std::size_t kDenseCellsPerTet = 8;
  /// Stage 1b in pieces (see above): begin_refresh() empties the overflow;
  /// each refresh_some_tets() revisits the next `max_tets` tets (hash order;
  /// tets of bodies that cannot move are skipped uncharged) and returns their
  /// work: work::kTetBox a tet, work::kCellInsert an overflow cell; `done`
  /// after the last; then build the overflow (mutable_overflow().begin_build(),
  /// build_some(), or build()) before the next query. begin_hash() drops
  /// the overflow.
  void begin_refresh();
  std::uint64_t refresh_some_tets(const World& world, const CollisionPairs& pairs, std::size_t max_tets, bool& done);
  SpatialHash& mutable_overflow() { return m_overflow; }
  /// The whole refresh at once (it calls begin_refresh() first), its tets' boxes and
  /// cell checks on the pool's threads (or the caller's without one), then
  /// the overflow inserted and built as hash_tets() builds the main table
  /// (SpatialHash::insert_all_and_build(): buckets in slot order): the same
  /// boxes, overflow and work as refresh_some_tets() to the end and a build,
  /// on any thread count. A build of the overflow afterwards does nothing.
  std::uint64_t refresh_tets(const World& world, const CollisionPairs& pairs, WorkerPool* pool = nullptr);
  /// Tets in the overflow of the last refresh (0 without one).
  std::size_t overflow_tets() const { return m_overflow_tets; }
  /// Tets the last hash_tets() left out before making their boxes (see
  /// there; 0 from begin_hash() on). For tests and benchmarks.
  std::size_t tets_unmade() const { return m_tets_unmade; }
  /// Whether the last hash_tets() entered its tets only into the cells
  /// that take them (see there; false from begin_hash() on).
  bool cells_told_apart() const { return m_told_apart; }
  /// Tets of every body (the global id range), hashed or not.
  std::size_t tet_count() const { return m_boxes.size(); }
  /// Stage 2 for one vertex; adds its work units to `work`. `margin_m` > 0
  /// (widened query): tets may have moved up to that far (m, max norm) since
  /// they were hashed, so every cell within margin_m of the point is
  /// searched and the stored AABBs are grown by it before the exact test
  /// with the current positions; then no tet that now holds the point is
  /// missed. margin_m = 0 is the paper's query: the point's cell only.
  std::optional<Contact> query_point(const World& world, const CollisionPairs& pairs, std::int32_t object,
                                     std::int32_t vertex, std::uint64_t& work, double margin_m = 0.0) {
    return query_point(world, pairs, object, vertex, work, margin_m, m_scratch);
  }
  /// What one query remembers (the tets it met, so a tet in several of its
  /// buckets is tested and charged once). One per thread: queries with their
  /// own scratch may run concurrently on an unchanging table and world.
  /// Aligned to a cache line: each query bumps `query`, and the scratches
  /// of two threads side by side in one line would pass it back and forth.
  struct alignas(64) QueryScratch {
    std::vector<std::uint32_t> tested;  ///< per slot: the last query that met it
    std::uint32_t query = 0;
    std::vector<std::uint64_t> candidates;  ///< one bucket's candidates: file id << 32 | slot
  };
  QueryScratch make_scratch() const { return QueryScratch{std::vector<std::uint32_t>(m_boxes.size(), 0), 0, {}}; }
  /// query_point() with the caller's scratch; the same answer and work.
  std::optional<Contact> query_point(const World& world, const CollisionPairs& pairs, std::int32_t object,
                                     std::int32_t vertex, std::uint64_t& work, double margin_m,
                                     QueryScratch& scratch) const;

  const SpatialHash& hash() const { return m_hash; }
  /// The union of body b's tet boxes (its non-degenerate tets, each as last
  /// hashed or refreshed; empty for a body the hash does not walk): on a
  /// dense hash_tets() where every vertex of b is in such a tet, the box
  /// around b's vertices, which has the same lo and hi (hash_tets()),
  /// from which the query's first test is made. Valid after a complete hash
  /// or refresh.
  const BoxUnion& body_box(std::size_t b) const { return m_body_boxes[b]; }
  /// Heap bytes of the tables, boxes and the single-threaded scratch.
  std::size_t memory_bytes() const;

 private:
  /// hash_some_tets()'s and refresh_some_tets()'s walk: from the cursor, the
  /// next max_tets tets (hash order) of bodies with a partner (and, if
  /// movable_only, that can move); each non-degenerate one gets its current
  /// AABB stored, then visit(slot) returns its work units.
  template <typename Visit>
  std::uint64_t walk_tets(const World& world, const CollisionPairs& pairs, bool movable_only, std::size_t max_tets,
                          bool& done, Visit&& visit);
  /// Stores the current AABB of the tet in slot `id` of body: what every
  /// hashing path (serial walk, parallel parts, refresh) records per tet.
  void store_box(const Body& body, std::uint32_t id);
  /// With refresh enabled, keeps the cells tet `id`'s stored box was hashed in.
  void record_hashed_cells(std::uint32_t id);
  /// Whether tet `id`'s stored box stays within the cells it was hashed in.
  bool within_hashed_cells(std::uint32_t id) const;
  /// Throws std::invalid_argument unless `world` has the bodies, each with
  /// the position and tet counts, that the detector was made for
  /// (constructor comment). At the start of each hash, refresh and walk.
  void check_world(const World& world) const;
  SpatialHash m_hash;
  SpatialHash m_overflow;                             // refresh only; allocated by enable_refresh()
  bool m_overflow_active = false;                     // queries search m_overflow too
  bool m_widening = false;                            // enable_widening(): the table always hashes
  std::size_t m_overflow_tets = 0;
  // Per slot (refresh only), the cell range it was hashed in, as
  // limits on its box's grid coordinates (SpatialHash::grid_coordinate):
  // lo[a] = first cell index, hi[a] = last cell index + 1. The box stays in
  // those cells when every lo coordinate >= lo and every hi coordinate < hi:
  // six comparisons, no floor (perf: the check of int64 cell indices, a
  // floor each, was 13.6 % of micro_peer_inside's BM_OursKeptTable).
  struct CellLimits {
    double lo[3], hi[3];
  };
  std::vector<CellLimits> m_hashed_cells;
  // refresh_tets(): the slots of the tets whose boxes left their cells, each
  // thread's (ascending) in its own list, a cache line apart as they grow;
  // then all of them in slot order, the overflow's input. The overflow is
  // then built from these tets alone, split evenly over the threads: over
  // all slots, a thread whose range held the one moving body built it alone
  // (BM_ThreadsPaired/0/125: 2 threads took 1.2x one thread's time).
  struct alignas(64) LeftIds {
    std::vector<std::uint32_t> ids;
  };
  std::vector<LeftIds> m_part_left;
  std::vector<std::uint32_t> m_left_ids;
  // Global tet id = offset[body] + tet (slots the same); one more entry, the
  // total, so a body's ids are [offset[body], offset[body + 1]).
  std::vector<std::uint32_t> m_body_tet_offset;
  std::vector<std::int32_t> m_owner;                  // global tet id or slot -> body (dense: the first filter)
  // The slots (file comment: "Tet numbering"): per slot, its global tet id
  // in the file's numbering, its vertex indices and whether it is
  // degenerate; per global tet id, its slot. Per-slot arrays are what the
  // hot loops read; per-id ones are read only by the piecewise walks.
  std::vector<std::uint32_t> m_file_id;
  std::vector<Tet> m_slot_tets;
  std::vector<char> m_slot_degenerate;
  std::vector<std::uint32_t> m_slot_of;
  // Per slot, a tet's AABB (at hashing time, or at the last refresh), lo and
  // hi side by side: the box test reads one record instead of two arrays.
  struct TetBox {
    Vec3 lo, hi;
  };
  std::vector<TetBox> m_boxes;
  // Per body, the union of its tets' boxes, kept by every path that stores
  // boxes (or its vertices' box, where hash_tets() says so); per body, the union over the other bodies the hash walks
  // (a superset of its enabled partners'), valid once a hash or refresh has
  // completed.
  std::vector<BoxUnion> m_body_boxes;
  std::vector<BoxUnion> m_partner_boxes;
  bool m_partner_boxes_ready = false;
  /// Per body, the box around the vertices of the other bodies the hash
  /// walks, so of every body that queries its tets (poisoned with
  /// self-collision): hash_tets() leaves out a tet strictly apart from it
  /// when its caller queries at the hash's positions only.
  std::vector<BoxUnion> m_query_reach;
  void reach_of_queries(const World& world, const CollisionPairs& pairs, const std::vector<BoxUnion>& vertices);
  /// Per cell of this epoch's dense grid, when hash_tets() leaves out what
  /// no query reaches: the walked body whose tagged vertices alone lie in
  /// it, kNoVertex (none) or kSeveralBodies (a vertex is tagged where its
  /// cell is within the cells of its body's m_query_reach: see
  /// tag_query_cells()). A tet of body b is entered into a
  /// cell only where that tag is neither kNoVertex nor m_own_tag[b] (b, or
  /// kNeverTag when b collides with itself): only points in a cell query it,
  /// and b's own points skip b's tets unread and uncharged. Kept at the
  /// largest grid's size, every cell kNoVertex but m_tagged_cells.
  std::vector<std::uint32_t> m_cell_tag;
  std::vector<std::uint32_t> m_tagged_cells;  // the cells the last tagging tagged
  std::vector<std::uint32_t> m_own_tag;
  // Per body, its vertices' first index in m_vertex_cell (one more entry,
  // the total); per vertex of a walked body, after tag_query_cells(), its
  // cell as offsets into the tagged grid (m_tag_grid).
  struct GridOffset {
    std::uint32_t i, j, k;
  };
  std::vector<std::uint32_t> m_body_vertex_offset;
  std::vector<GridOffset> m_vertex_cell;
  // Per walked body, after tag_query_cells(): the cells of its
  // m_query_reach, as offsets (the whole grid with self-collision).
  struct GridOffsetRange {
    GridOffset lo, hi;
  };
  std::vector<GridOffsetRange> m_reach_cells;
  std::vector<char> m_ask_untagged;  // per body: hash_tets() asks cells_if_none_takes() first
  SpatialHash::GridShape m_tag_grid{};
  // Per body: every vertex lies in one of its non-degenerate tets, so the
  // union of its tets' boxes is the box around its vertices, exactly where
  // the coordinates are finite (min and max round nothing).
  std::vector<char> m_vertices_in_tets;
  static constexpr std::uint32_t kNoVertex = UINT32_MAX;
  static constexpr std::uint32_t kSeveralBodies = UINT32_MAX - 1;
  static constexpr std::uint32_t kNeverTag = UINT32_MAX - 2;  // no cell has this tag
  /// Whether a cell tagged `tag` takes a tet of a body whose own tag is
  /// `own` (m_own_tag): a vertex lies in it, and not only the body's own.
  static bool takes(std::uint32_t tag, std::uint32_t own) { return (tag != kNoVertex) & (tag != own); }
  std::size_t m_tets_unmade = 0;
  bool m_told_apart = false;
  /// Fills m_cell_tag, m_own_tag, m_vertex_cell, m_reach_cells and
  /// m_ask_untagged from the walked bodies' vertices; returns false where
  /// tags would not pay (every walked body has a quarter or more of its
  /// vertices in cells that take its tets, as every self-colliding body
  /// has), or if a vertex lies outside the grid, which the grid's range
  /// rules out; the tags are not used then.
  bool tag_query_cells(const World& world, const CollisionPairs& pairs);
  /// With the tags in use, the cells of slot `id`'s box, from its vertices'
  /// m_vertex_cell (cell_of is monotone, so a box's first and last cell
  /// along an axis are its vertices' least and greatest): their number
  /// where no tag of them takes a tet of `body`, so the tet would enter no
  /// cell; 0 where one would, or where the box has more than
  /// kMaxCellsPerBox cells (the insert then decides, and throws).
  std::size_t cells_if_none_takes(std::uint32_t id, std::size_t body) const;
  /// Makes m_partner_boxes from m_body_boxes after a complete hash or refresh.
  void finish_body_boxes(const World& world, const CollisionPairs& pairs);
  QueryScratch m_scratch;                             // the single-threaded queries'
  std::size_t m_hash_body = 0, m_hash_tet = 0;        // hash_some_tets()'s and refresh_some_tets()'s cursor
};

/// The O(points x tets) reference: tests the vertex against every tet of every
/// enabled body with the same exact predicate and the same smallest-index rule,
/// no hashing and no AABBs. For tests.
std::optional<Contact> brute_force_query_point(const World& world, const CollisionPairs& pairs, std::int32_t object,
                                               std::int32_t vertex, std::uint64_t& work);

}  // namespace tcb
