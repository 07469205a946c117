#pragma once
/// Spatial hashing over an infinite uniform grid (Teschner et al., "Optimized
/// Spatial Hashing for Collision Detection of Deformable Objects", VMV 2003).
///
/// Items (tets, triangles: any 32-bit id) are inserted into every grid cell
/// their axis-aligned box overlaps; cell (i, j, k) = floor(x / cell_size) maps
/// to one of `table_size` buckets (a prime) by one of two hash functions:
/// - HashFunction::Paper: ((i * 73856093) xor (j * 19349663) xor (k * 83492791))
///   mod n, computed in unsigned 64-bit arithmetic (the paper's, kept for
///   comparison; symmetric around the origin: (-10,-1,9) and (-10,1,-9)
///   collide, and stacked plates sit exactly there);
/// - HashFunction::Mixed (default): a multiply-add of the cell indices followed
///   by the 64-bit splitmix finaliser, mod n.
/// (mod n by multiplications, fast_modulo.hpp: exactly %, without a division.)
/// Buckets are time-stamped: begin_epoch() empties the whole table in O(1) (a
/// bucket whose stamp is older counts as empty), so nothing is cleared per step.
/// Insertion appends entries; build() then lays each bucket's entries out
/// contiguously by a counting sort in O(entries), never touching the rest of the
/// table (so the time-stamp property holds). Queries need a built table:
/// insert everything, build(), then query. (Walking per-bucket linked lists
/// instead made every candidate a cache miss: 2.2 us per point query on the
/// dog pair.)
/// A bucket may hold items of other cells (hash collisions) and an item several
/// times (several of its cells in one bucket): callers filter by their own
/// exact tests and de-duplicate. A bucket lists its entries in insertion order
/// (every build is a stable sort), so a caller that inserts ascending ids
/// gets every bucket sorted, and may search it.
/// A dense grid in place of the hash (begin_epoch_dense()): for a table whose
/// boxes all lie in a box known before the first insert, each cell of that
/// box's cell range gets a bucket of its own, numbered along k, then j, then
/// i (no hash, no modulo, no two cells in one bucket; neighbouring cells'
/// buckets side by side). A point outside the range has an empty bucket.
/// Every bucket then lists exactly the items of its cell (those a caller's
/// `keep` accepts, insert_all_and_build()), in insertion order: the entries
/// of the point's own bucket that pass a caller's box test are the hash's, in the hash's order (a box holding p covers p's
/// cell, so it is in p's bucket either way; a colliding cell's items differ
/// only by failing that test). What differs is only where a bucket lists
/// items of other cells: a search over several buckets meets those in
/// another order, so a caller whose work counts the order of a multi-cell
/// search keeps the hash (design notes: a dense grid over the tets' cell
/// range measured about 30 % faster than hashing).
/// Contract: coordinates must be finite; cell indices are clamped to +-2^50,
/// far beyond any scene (positions are in metres). A box covering more than
/// kMaxCellsPerBox cells throws HashOverflow instead of exhausting memory:
/// either the cell size is far too small for the elements, or the simulation
/// has diverged and an element has been stretched across the scene.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "method/detection/fast_modulo.hpp"
#include "sim/mesh/tet_mesh.hpp"
#include "sim/parallel/worker_pool.hpp"

namespace tcb {

enum class HashFunction { Paper, Mixed };

inline constexpr std::uint64_t kMaxCellsPerBox = std::uint64_t(1) << 21;

class HashOverflow : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The cell hash in two parts, so a box's cells along k cost one addition
/// and the finish, not three multiplications: both functions combine a term
/// of (i, j) with k * K (mod 2^64), and (k + 1) * K = k * K + K.
template <HashFunction function>
struct CellHashParts {
  static constexpr std::uint64_t kI = function == HashFunction::Paper ? 73856093ULL : 0x9E3779B97F4A7C15ULL;
  static constexpr std::uint64_t kJ = function == HashFunction::Paper ? 19349663ULL : 0xC2B2AE3D27D4EB4FULL;
  static constexpr std::uint64_t kK = function == HashFunction::Paper ? 83492791ULL : 0x165667B19E3779F9ULL;
  static std::uint64_t ij(std::int64_t i, std::int64_t j) {
    const auto ui = static_cast<std::uint64_t>(i), uj = static_cast<std::uint64_t>(j);
    if constexpr (function == HashFunction::Paper) return (ui * kI) ^ (uj * kJ);
    else return ui * kI + uj * kJ;
  }
  static std::uint64_t k_term(std::int64_t k) { return static_cast<std::uint64_t>(k) * kK; }
  /// The hash from ij(i, j) and k_term(k).
  static std::uint64_t finish(std::uint64_t ij_part, std::uint64_t k_part) {
    if constexpr (function == HashFunction::Paper) {
      return ij_part ^ k_part;
    } else {  // the splitmix64 finaliser
      std::uint64_t z = ij_part + k_part;
      z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
      z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
      return z ^ (z >> 31);
    }
  }
};

/// The cell's 64-bit hash, before it is reduced modulo the table size:
/// Paper ((i * 73856093) xor (j * 19349663) xor (k * 83492791)), or Mixed
/// (i * A + j * B + k * C, then the splitmix64 finaliser), in unsigned
/// 64-bit arithmetic (inline: it runs for every query).
inline std::uint64_t hash_cell(HashFunction function, std::int64_t i, std::int64_t j, std::int64_t k) {
  if (function == HashFunction::Paper) {
    using H = CellHashParts<HashFunction::Paper>;
    return H::finish(H::ij(i, j), H::k_term(k));
  }
  using H = CellHashParts<HashFunction::Mixed>;
  return H::finish(H::ij(i, j), H::k_term(k));
}

/// Smallest prime >= n (n >= 2).
std::uint64_t next_prime(std::uint64_t n);

class SpatialHash {
 public:
  SpatialHash() = default;
  SpatialHash(double cell_size_m, std::size_t table_size, HashFunction function);

  /// Empties the table in O(1); the table hashes.
  void begin_epoch();
  /// Empties the table and makes it a dense grid over the cells of box
  /// [lo, hi] (file comment), if that range has at most max_cells cells
  /// (and its coordinates are finite); returns whether it did. Otherwise
  /// the table hashes, as after begin_epoch(). Every box inserted until the
  /// next epoch must lie in [lo, hi] (a box reaching a cell outside the
  /// range throws std::logic_error: its entries would be lost). The
  /// buckets grow to the range's cell count (12 bytes a cell) and are kept.
  bool begin_epoch_dense(const Vec3& lo, const Vec3& hi, std::size_t max_cells);
  /// Whether this epoch's table is a dense grid.
  bool dense() const { return m_dense; }
  /// A dense grid's cells (its buckets' count this epoch); 0 when the table hashes.
  std::size_t grid_cells() const { return m_dense ? active_buckets() : 0; }
  /// The index of point p's cell in this epoch's dense grid, which is its
  /// bucket (what cell_entries(p) reads); kOutsideGrid where the cell lies
  /// outside the grid, or the table hashes.
  std::size_t grid_cell(const Vec3& p) const { return grid_cell(cell_of(p.x()), cell_of(p.y()), cell_of(p.z())); }
  /// The same for the cell of indices (i, j, k) (cell_of's).
  std::size_t grid_cell(std::int64_t i, std::int64_t j, std::int64_t k) const {
    if (!m_dense) return kOutsideGrid;
    // Unsigned (no signed overflow, whatever the index): a cell below the
    // range wraps above it.
    const auto u = [](std::int64_t x) { return static_cast<std::uint64_t>(x); };
    const std::uint64_t di = u(i) - u(m_grid.i0), dj = u(j) - u(m_grid.j0), dk = u(k) - u(m_grid.k0);
    if (di >= m_grid_n[0] || dj >= m_grid_n[1] || dk >= m_grid_n[2]) return kOutsideGrid;
    return static_cast<std::size_t>((di * m_grid_n[1] + dj) * m_grid_n[2] + dk);
  }
  static constexpr std::size_t kOutsideGrid = std::numeric_limits<std::size_t>::max();
  /// This epoch's dense grid: its first cell's indices and its cells along
  /// each axis. Cell (first[0] + di, first[1] + dj, first[2] + dk) is bucket
  /// (di * cells[1] + dj) * cells[2] + dk, what grid_cell() returns: for
  /// callers that keep cells as offsets into the grid and walk a box's
  /// cells from them. Each count is below 2^32 (the grid's cells are).
  /// Meaningful only while dense().
  struct GridShape {
    std::int64_t first[3];
    std::uint64_t cells[3];
    /// The bucket of the cell at offsets (di, dj, dk) into the grid.
    std::size_t index(std::uint64_t di, std::uint64_t dj, std::uint64_t dk) const {
      return static_cast<std::size_t>((di * cells[1] + dj) * cells[2] + dk);
    }
  };
  GridShape grid_shape() const {
    return {{m_grid.i0, m_grid.j0, m_grid.k0}, {m_grid_n[0], m_grid_n[1], m_grid_n[2]}};
  }
  /// Inserts item into every cell its box [lo, hi] overlaps; returns the
  /// number of cells (each a unit of work).
  std::size_t insert_box(const Vec3& lo, const Vec3& hi, std::uint32_t item);
  /// The cells insert_box(lo, hi, .) would insert into (its work), without
  /// touching the table; a double, so an absurd box neither overflows nor
  /// throws here (insert_box() throws for it).
  double cells_of_box(const Vec3& lo, const Vec3& hi) const;
  /// Makes the inserted entries queryable (see file comment).
  void build();
  /// build() in pieces, for interruptible callers: begin_build(), then
  /// build_some() until it returns true. Each call visits at most
  /// `max_visits` entries (the sort makes three passes over them); the
  /// result is exactly build()'s. Nothing may be inserted or queried until
  /// it is done. After insert_all_and_build() the table is built: build()
  /// and build_some() then do nothing (build_some() returns true).
  void begin_build();
  bool build_some(std::size_t max_visits);

  /// insert_all_and_build()'s `keep` where a caller gives none.
  struct KeepEveryEntry {
    struct EveryCell {
      constexpr bool operator()(std::uint32_t) const { return true; }
    };
    constexpr EveryCell operator()(std::uint32_t) const { return {}; }
  };

  /// insert_box() for the boxes i = 0 .. n-1 in order, then build(), on the
  /// pool's threads: box_of(i, lo, hi, item) gives box i, or returns false
  /// to skip it (or box_of(part, i, lo, hi, item), if it takes the calling
  /// thread's part, 0 .. threads - 1: for per-thread accumulators). Without
  /// `keep`, the table is exactly the serial one: the same items in every
  /// bucket, in insertion order (only where each bucket's range sits in the sorted
  /// array differs, which no query sees). Returns the cells inserted.
  /// Each thread takes a contiguous range of boxes and computes their cells'
  /// buckets into one list per owner (in order); an owner is a contiguous
  /// range of at most `buckets_per_owner` buckets (a power of two), and there
  /// are at least kOwnersPerThread owners a thread on several threads (at
  /// least one on one) where the table has as many buckets. Then each
  /// owner's buckets are counted, placed and filled from the lists meant for
  /// it, read in thread order, owners handed to threads as they come free,
  /// so no two threads write one bucket. Small owners keep the build's random accesses
  /// to the buckets and the sorted items in a core's cache, which is why a
  /// pool of one thread builds this way too (the serial insert_box() and
  /// build() touch the whole table for every entry). box_of runs concurrently
  /// on disjoint i: each thread calls it for one contiguous range of i, in
  /// ascending order (so a caller may keep a cursor a part).
  /// A HashOverflow is thrown for the first offending box, as serially.
  /// Call it on an empty table (right after begin_epoch()). With
  /// `cells_of_box` given (n values), cells_of_box[i] receives the cells box
  /// i was inserted into (what insert_box() returns for it; 0 for a box
  /// skipped), for callers that charge each box's work (after a throw,
  /// some values are left unwritten).
  /// `keep`, where given, decides each entry: keep(item) is called once a
  /// box and returns a predicate on its buckets, and an entry that
  /// predicate refuses is not entered, but its cell is still counted (in
  /// the return value and cells_of_box), as the work the insert was
  /// charged. Both run concurrently, so must be pure functions of their
  /// arguments; then the table is still the same on every thread count.
  template <typename BoxOf, typename KeepEntry = KeepEveryEntry>
  std::size_t insert_all_and_build(std::size_t n, BoxOf&& box_of, WorkerPool& pool,
                                   std::size_t buckets_per_owner = kBucketsPerOwner,
                                   std::uint64_t* cells_of_box = nullptr, KeepEntry keep = {});

  /// 16384 buckets of 12 bytes: 192 KiB, within a core's L2 beside the
  /// owner's slice of the sorted items.
  static constexpr std::size_t kBucketsPerOwner = 16384;
  static constexpr std::size_t kOwnersPerThread = 8;
  static constexpr std::size_t kKeptBatch = 32;  // insert_all_and_build()'s kept cells, pushed in batches

  /// Calls f(item) for every entry of the bucket of point p's cell.
  template <typename F>
  void for_each_in_cell(const Vec3& p, F&& f) const {
    const Entries entries = cell_entries(p);
    for (const std::uint32_t* it = entries.first; it != entries.last; ++it) f(*it);
  }
  /// The entries of the bucket of point p's cell, [first, last): what
  /// for_each_in_cell() visits, as a range a caller loops over itself (its
  /// loop state then stays in registers).
  struct Entries {
    const std::uint32_t* first;
    const std::uint32_t* last;
  };
  Entries cell_entries(const Vec3& p) const {
    if (m_dense) {
      const std::size_t c = grid_cell(p);
      return c == kOutsideGrid ? Entries{nullptr, nullptr} : bucket_entries(c);
    }
    return bucket_entries(bucket_of(cell_of(p.x()), cell_of(p.y()), cell_of(p.z())));
  }
  /// Calls f(first, last) with the entries of every bucket of the cells box
  /// [lo, hi] overlaps (a bucket once a cell, so possibly repeatedly), each
  /// in insertion order; returns the number of cells visited.
  template <typename F>
  std::size_t for_each_range_in_box(const Vec3& lo, const Vec3& hi, F&& f) const {
    return buckets_of_box(lo, hi, [&](std::uint32_t b) {
      const Entries entries = bucket_entries(b);
      if (entries.first != entries.last) f(entries.first, entries.last);
    });
  }
  /// The number of cells for_each_range_in_box(lo, hi, .) visits (and its
  /// HashOverflow for an absurd box), without visiting them.
  std::size_t cells_visited(const Vec3& lo, const Vec3& hi) const {
    return cell_range(lo, hi).cells();
  }
  /// Calls f(item) for every entry of every bucket of the cells box [lo, hi]
  /// overlaps; returns the number of cells visited.
  template <typename F>
  std::size_t for_each_in_box(const Vec3& lo, const Vec3& hi, F&& f) const {
    return buckets_of_box(lo, hi, [&](std::uint32_t b) { for_each_in_bucket(b, f); });
  }

  double cell_size_m() const { return m_cell_size; }
  HashFunction function() const { return m_function; }
  /// x in cell units, clamped: cell_of(x) is its floor. So for an integer
  /// c with |c| <= 2^50 (every cell index), cell_of(x) >= c exactly when
  /// grid_coordinate(x) >= c, and cell_of(x) <= c exactly when
  /// grid_coordinate(x) < c + 1: comparisons that need no floor.
  double grid_coordinate(double x) const {
    constexpr double kLimit = 1125899906842624.0;  // 2^50
    return std::clamp(x * m_inverse_cell, -kLimit, kLimit);
  }
  /// The grid index of coordinate x along any axis: floor(x * (1 / cell size)),
  /// clamped (the inverse is taken once; at a cell border it may differ from
  /// floor(x / cell size) by one, the same for every caller).
  std::int64_t cell_of(double x) const {
    // floor by truncation and a step down for negative non-integers:
    // exactly std::floor for every clamped value (its integer part is a
    // double, so the truncation is exact), and clamping first gives the same
    // as after, the limits being integers. std::floor on the baseline x86-64 target (no SSE4.1
    // round) is a dozen instructions, six times a box.
    const double y = grid_coordinate(x);
    const auto t = static_cast<std::int64_t>(y);
    return t - static_cast<std::int64_t>(static_cast<double>(t) > y);  // no branch: signs mix near the origin
  }
  /// The hash's bucket count (the constructor's table_size): what a table
  /// made to match this one takes, whichever form this epoch's has.
  std::size_t table_size() const { return m_hash_buckets; }
  std::size_t entry_count() const { return m_built_in_parts ? m_sorted.size() : m_entries.size(); }
  /// Buckets holding at least one entry in the current epoch.
  std::size_t occupied_buckets() const;
  /// Heap bytes of the table and its lists (heap_bytes.hpp).
  std::size_t memory_bytes() const;

 private:
  struct Entry {
    std::uint32_t item;
    std::uint32_t bucket;
  };
  void check_box(std::int64_t ni, std::int64_t nj, std::int64_t nk) const;
  /// Calls sink(bucket) for each cell box [lo, hi] overlaps, in insertion
  /// order, without touching the table; returns the number of cells. Safe to
  /// call concurrently.
  /// Inserting: the box must lie in a dense grid's range (std::logic_error
  /// otherwise); else the cells outside the range (empty buckets) are
  /// counted but not passed to sink.
  template <bool inserting = false, typename Sink>
  std::size_t buckets_of_box(const Vec3& lo, const Vec3& hi, Sink&& sink) const {
    const CellRange r = cell_range(lo, hi);
    if (m_dense) {
      dense_buckets_of_cells<inserting>(r, sink);
      return r.cells();
    }
    if (m_function == HashFunction::Paper)
      buckets_of_cells<HashFunction::Paper>(r.i0, r.i1, r.j0, r.j1, r.k0, r.k1, sink);
    else
      buckets_of_cells<HashFunction::Mixed>(r.i0, r.i1, r.j0, r.j1, r.k0, r.k1, sink);
    return r.cells();
  }
  /// The cells box [lo, hi] overlaps, checked (HashOverflow if absurd).
  struct CellRange {
    std::int64_t i0, i1, j0, j1, k0, k1;
    std::size_t cells() const { return static_cast<std::size_t>((i1 - i0 + 1) * (j1 - j0 + 1) * (k1 - k0 + 1)); }
  };
  CellRange cell_range(const Vec3& lo, const Vec3& hi) const {
    const CellRange r{cell_of(lo.x()), cell_of(hi.x()), cell_of(lo.y()), cell_of(hi.y()), cell_of(lo.z()), cell_of(hi.z())};
    const std::int64_t ni = r.i1 - r.i0 + 1, nj = r.j1 - r.j0 + 1, nk = r.k1 - r.k0 + 1;
    // The common box decided here, inline: each side 1 to kMaxCellsPerBox
    // cells (so the unsigned product, at most 2^63, is exact, and so is
    // check_box()'s double product wherever it is within the limit, 2^21)
    // and the product within the limit: check_box() would pass it. Any
    // other box goes to check_box(), which decides as before. (A call a box
    // was 3 % of the dog pair's cycle in perf.)
    constexpr auto kMax = static_cast<std::int64_t>(kMaxCellsPerBox);
    const auto u = [](std::int64_t x) { return static_cast<std::uint64_t>(x); };
    const bool common = ni >= 1 && nj >= 1 && nk >= 1 && ni <= kMax && nj <= kMax && nk <= kMax &&
                        u(ni) * u(nj) * u(nk) <= kMaxCellsPerBox;
    if (!common) check_box(ni, nj, nk);
    return r;
  }
  /// buckets_of_box()'s loop for one hash function (the function chosen once
  /// a box, the k term stepped by addition).
  template <HashFunction function, typename Sink>
  void buckets_of_cells(std::int64_t i0, std::int64_t i1, std::int64_t j0, std::int64_t j1, std::int64_t k0,
                        std::int64_t k1, Sink& sink) const {
    using H = CellHashParts<function>;
    // A local copy: the sink's stores could alias the table's members, which
    // the compiler then reloads for every cell.
    const FastModulo modulo = m_modulo;
    const std::uint64_t k_first = H::k_term(k0);
    for (std::int64_t i = i0; i <= i1; ++i)
      for (std::int64_t j = j0; j <= j1; ++j) {
        const std::uint64_t ij = H::ij(i, j);
        std::uint64_t k_part = k_first;
        for (std::int64_t k = k0; k <= k1; ++k, k_part += H::kK)
          sink(static_cast<std::uint32_t>(modulo(H::finish(ij, k_part))));
      }
  }
  /// buckets_of_box()'s loop for a dense grid: the range clipped to the grid
  /// (or, inserting, checked to lie in it).
  template <bool inserting, typename Sink>
  void dense_buckets_of_cells(const CellRange& r, Sink& sink) const {
    const CellRange& g = m_grid;
    const CellRange c{std::max(r.i0, g.i0), std::min(r.i1, g.i1), std::max(r.j0, g.j0),
                      std::min(r.j1, g.j1), std::max(r.k0, g.k0), std::min(r.k1, g.k1)};
    if constexpr (inserting)
      if (c.i0 != r.i0 || c.i1 != r.i1 || c.j0 != r.j0 || c.j1 != r.j1 || c.k0 != r.k0 || c.k1 != r.k1)
        throw_outside_grid();
    const auto nj = static_cast<std::int64_t>(m_grid_n[1]), nk = static_cast<std::int64_t>(m_grid_n[2]);
    for (std::int64_t i = c.i0; i <= c.i1; ++i)
      for (std::int64_t j = c.j0; j <= c.j1; ++j) {
        const std::int64_t row = ((i - g.i0) * nj + (j - g.j0)) * nk - g.k0;
        for (std::int64_t k = c.k0; k <= c.k1; ++k) sink(static_cast<std::uint32_t>(row + k));
      }
  }
  [[noreturn]] static void throw_outside_grid();
  /// Buckets in use this epoch: the grid's cells, or the hash's buckets.
  std::size_t active_buckets() const {
    return m_dense ? static_cast<std::size_t>(m_grid_n[0] * m_grid_n[1] * m_grid_n[2]) : m_hash_buckets;
  }
  /// Counts one more entry in bucket b (emptying it first if its stamp is
  /// stale); returns whether this was its first entry of the epoch.
  bool count_entry(std::uint32_t b) {
    Bucket& bucket = m_buckets[b];
    const bool first = bucket.stamp != m_epoch;
    if (first) {
      bucket.stamp = m_epoch;
      bucket.count = 0;
    }
    ++bucket.count;
    return first;
  }
  /// The owner of bucket b when owners hold 2^shift buckets each.
  static std::size_t owner_of(std::size_t b, int shift) { return b >> shift; }
  /// Thread p's list of entries for owner q's buckets, with `owners` owners
  /// (the layout is described at m_part_entries).
  std::vector<Entry>& part_list(std::size_t p, std::size_t q, std::size_t owners) {
    return m_part_entries[p * (owners + kHeaderPad) + q];
  }
  /// insert_all_and_build()'s second half: each owner's buckets are counted,
  /// placed and filled from m_part_entries, owners spread over the threads.
  void build_parallel(WorkerPool& pool, std::size_t owners);
  std::size_t bucket_of(std::int64_t i, std::int64_t j, std::int64_t k) const {
    return static_cast<std::size_t>(m_modulo(hash_cell(m_function, i, j, k)));
  }
  /// Bucket b's entries (empty when its stamp is stale).
  Entries bucket_entries(std::size_t b) const {
    const Bucket& bucket = m_buckets[b];
    if (bucket.stamp != m_epoch) return {nullptr, nullptr};
    const std::uint32_t* first = m_sorted.data() + bucket.start;
    return {first, first + bucket.count};
  }
  template <typename F>
  void for_each_in_bucket(std::size_t b, F& f) const {
    const Entries entries = bucket_entries(b);
    for (const std::uint32_t* it = entries.first; it != entries.last; ++it) f(*it);
  }

  double m_cell_size = 1.0;
  double m_inverse_cell = 1.0;
  HashFunction m_function = HashFunction::Mixed;
  // A bucket's three words side by side: inserting, building and querying
  // touch one cache line per bucket instead of three (the table is larger
  // than the caches on big scenes, and buckets are reached in random order).
  struct Bucket {
    std::uint32_t stamp = 0;  ///< the epoch it was last written in; older = empty
    std::uint32_t count = 0;  ///< entries, valid where stamp == m_epoch
    std::uint32_t start = 0;  ///< first entry in m_sorted (after build)
  };
  std::vector<Bucket> m_buckets;
  std::size_t m_hash_buckets = 1;  ///< the hash's bucket count (m_buckets may be larger: a grid's)
  FastModulo m_modulo;  ///< modulo m_hash_buckets
  bool m_dense = false;  ///< this epoch's table is a dense grid over m_grid
  CellRange m_grid{0, 0, 0, 0, 0, 0};
  std::uint64_t m_grid_n[3] = {1, 1, 1};  ///< the grid's cells along i, j, k
  std::uint32_t m_epoch = 1;
  std::vector<Entry> m_entries;   // in insertion order
  std::vector<std::uint32_t> m_sorted;  // items grouped by bucket (after build)
  // insert_all_and_build()'s lists: part_list(p, q, owners) holds the entries
  // thread p made for the buckets owner q owns, in insertion order (kept
  // between epochs, so they do not regrow).
  std::vector<std::vector<Entry>> m_part_entries;
  std::vector<std::vector<std::uint32_t>> m_part_touched;  // per thread: its owner's buckets, in first-met order
  // Thread p's lists start at m_part_entries[p * (owners + kHeaderPad)] (and
  // its touched list at m_part_touched[p * kHeaderPad]): kHeaderPad empty list
  // headers between two threads' keep the headers each thread pushes to
  // (their end pointers change at every entry) off the other's cache lines.
  // With the headers adjacent, plates20's tet hash on 2 threads took
  // 1.5-1.7 ms against 1.2 ms on one; apart, 0.83-0.93 ms
  // (micro_collision_cycle, ms_hash_tets).
  static constexpr std::size_t kHeaderPad = (64 + sizeof(std::vector<Entry>) - 1) / sizeof(std::vector<Entry>);
  bool m_built_in_parts = false;  // this epoch's table came from insert_all_and_build() (m_entries is empty)
  int m_build_pass = 3;                 // 0..2 while a build is under way, 3 when built
  std::size_t m_build_cursor = 0;
  std::uint32_t m_build_next = 0;
};

template <typename BoxOf, typename KeepEntry>
std::size_t SpatialHash::insert_all_and_build(std::size_t n, BoxOf&& box_of, WorkerPool& pool,
                                              std::size_t buckets_per_owner, std::uint64_t* cells_of_box,
                                              KeepEntry keep) {
  if (!m_entries.empty() || m_built_in_parts)
    throw std::logic_error("SpatialHash::insert_all_and_build needs an empty table");
  const std::size_t parts = static_cast<std::size_t>(pool.threads());
  // Owners of 2^shift buckets (so a bucket's owner is a shift, not a
  // division): the largest power of two within buckets_per_owner, made
  // smaller on several threads as below.
  int shift = 0;
  while (shift < 40 && (std::size_t(2) << shift) <= buckets_per_owner) ++shift;  // 2^40 buckets: beyond any table
  const auto owners_of = [&](int s) { return (active_buckets() + (std::size_t(1) << s) - 1) >> s; };
  // On several threads, at least kOwnersPerThread owners a thread (where the
  // table has that many buckets), which the build hands out as threads come
  // free: a few large owners split unevenly (9 on the dog pair: 5 and 4).
  const std::size_t least_owners = parts > 1 ? kOwnersPerThread * parts : 1;
  while (shift > 0 && owners_of(shift) < least_owners) --shift;
  const std::size_t owners = owners_of(shift);
  m_part_entries.resize(parts * (owners + kHeaderPad));
  // Every list emptied here, not by its part: a part with an empty range
  // never runs, and must not leave last epoch's entries behind.
  for (std::vector<Entry>& list : m_part_entries) list.clear();
  std::vector<std::size_t> cells(parts, 0);
  pool.for_ranges(n, [&](int part, std::size_t begin, std::size_t end) {
    const std::size_t p = static_cast<std::size_t>(part);
    std::vector<Entry>* lists = &part_list(p, 0, owners);
    const int owner_shift = shift;  // in a register, not reloaded after every push
    Vec3 lo, hi;
    std::uint32_t item = 0;
    std::size_t count = 0;  // summed here, stored once: cells[] is one cache line for all parts
    for (std::size_t i = begin; i < end; ++i) {
      bool kept;
      if constexpr (std::is_invocable_v<BoxOf&, int, std::size_t, Vec3&, Vec3&, std::uint32_t&>) {
        kept = box_of(part, i, lo, hi, item);
      } else {
        kept = box_of(i, lo, hi, item);
      }
      if (!kept) {
        if (cells_of_box) cells_of_box[i] = 0;
        continue;
      }
      std::size_t box_cells = 0;
      if constexpr (std::is_same_v<KeepEntry, KeepEveryEntry>) {
        box_cells = buckets_of_box<true>(
            lo, hi, [&](std::uint32_t b) { lists[owner_of(b, owner_shift)].push_back({item, b}); });
      } else {
        // Where most cells are refused, a branch on each was mispredicted
        // often: the cells are gathered without one (each written, counted
        // if kept), and only the kept ones pushed. The dog pair's tet hash
        // (TetHashDetector, one thread, 300 hashes timed in a throwaway
        // test, not kept): 3.63 ms with a branch a cell, 2.70 ms so.
        const auto keep_cell = keep(item);
        std::uint32_t kept_cells[kKeptBatch];
        std::size_t kept_count = 0;
        const auto push_kept = [&] {
          for (std::size_t k = 0; k < kept_count; ++k)
            lists[owner_of(kept_cells[k], owner_shift)].push_back({item, kept_cells[k]});
          kept_count = 0;
        };
        box_cells = buckets_of_box<true>(lo, hi, [&](std::uint32_t b) {
          kept_cells[kept_count] = b;
          kept_count += keep_cell(b) ? 1 : 0;
          if (kept_count == kKeptBatch) push_kept();
        });
        push_kept();
      }
      if (cells_of_box) cells_of_box[i] = box_cells;
      count += box_cells;
    }
    cells[p] = count;
  });
  build_parallel(pool, owners);
  std::size_t inserted = 0;
  for (std::size_t c : cells) inserted += c;
  return inserted;
}

}  // namespace tcb
