#include "method/detection/spatial_hash.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "method/handler/heap_bytes.hpp"

namespace tcb {

std::uint64_t next_prime(std::uint64_t n) {
  if (n <= 2) return 2;
  for (std::uint64_t c = n | 1;; c += 2) {
    bool prime = true;
    for (std::uint64_t d = 3; d * d <= c; d += 2)
      if (c % d == 0) {
        prime = false;
        break;
      }
    if (prime) return c;
  }
}

SpatialHash::SpatialHash(double cell_size_m, std::size_t table_size, HashFunction function)
    : m_cell_size(cell_size_m), m_inverse_cell(1.0 / cell_size_m), m_function(function),
      m_buckets(std::max<std::size_t>(table_size, 1)), m_hash_buckets(m_buckets.size()), m_modulo(m_hash_buckets) {
  // A subnormal size has an infinite inverse: cell_of(0) would be 0 x inf,
  // a NaN cast to an integer (undefined).
  if (!(cell_size_m > 0.0) || !std::isfinite(cell_size_m) || !std::isfinite(m_inverse_cell))
    throw std::invalid_argument("spatial hash cell size must be positive and finite, and its inverse finite");
}

void SpatialHash::begin_epoch() {
  ++m_epoch;
  if (m_epoch == 0) {  // wrapped after 2^32 epochs: reset the stamps once
    for (Bucket& b : m_buckets) b.stamp = 0;
    m_epoch = 1;
  }
  m_entries.clear();
  m_built_in_parts = false;
  m_dense = false;
}

bool SpatialHash::begin_epoch_dense(const Vec3& lo, const Vec3& hi, std::size_t max_cells) {
  begin_epoch();
  if (!lo.allFinite() || !hi.allFinite() || (lo.array() > hi.array()).any()) return false;
  const std::int64_t first[3] = {cell_of(lo.x()), cell_of(lo.y()), cell_of(lo.z())};
  const std::int64_t last[3] = {cell_of(hi.x()), cell_of(hi.y()), cell_of(hi.z())};
  double cells = 1.0;
  for (int a = 0; a < 3; ++a) cells *= static_cast<double>(last[a] - first[a] + 1);
  // Bucket indices are 32-bit (Entry::bucket).
  if (cells > static_cast<double>(max_cells) || cells > static_cast<double>(UINT32_MAX)) return false;
  m_grid = CellRange{first[0], last[0], first[1], last[1], first[2], last[2]};
  for (int a = 0; a < 3; ++a) m_grid_n[a] = static_cast<std::uint64_t>(last[a] - first[a] + 1);
  // New buckets carry stamp 0, older than every epoch: empty.
  if (m_buckets.size() < static_cast<std::size_t>(cells)) m_buckets.resize(static_cast<std::size_t>(cells));
  m_dense = true;
  return true;
}

void SpatialHash::throw_outside_grid() {
  throw std::logic_error("SpatialHash: a box inserted into a dense grid reaches a cell outside its range");
}

void SpatialHash::check_box(std::int64_t ni, std::int64_t nj, std::int64_t nk) const {
  const double cells = static_cast<double>(ni) * static_cast<double>(nj) * static_cast<double>(nk);
  if (cells > static_cast<double>(kMaxCellsPerBox))
    throw HashOverflow("a box spans " + std::to_string(cells) + " hash cells of " + std::to_string(m_cell_size) +
                       " m: the simulation has diverged, or collision.cell_size is far too small for the elements");
}

double SpatialHash::cells_of_box(const Vec3& lo, const Vec3& hi) const {
  double cells = 1.0;
  for (int a = 0; a < 3; ++a) cells *= static_cast<double>(cell_of(hi[a]) - cell_of(lo[a]) + 1);
  return cells;
}

std::size_t SpatialHash::insert_box(const Vec3& lo, const Vec3& hi, std::uint32_t item) {
  return buckets_of_box<true>(lo, hi, [&](std::uint32_t b) {
    m_entries.push_back({item, b});
    count_entry(b);
  });
}

void SpatialHash::build_parallel(WorkerPool& pool, std::size_t owners) {
  // The serial build's counting sort, per owner on its own buckets: count
  // (noting buckets in first-met order), give each bucket its range after
  // the ranges of lower owners, then fill the ranges from the back reading
  // entries backwards (a bucket's start ends where its range starts, and its
  // items stay in insertion order).
  const std::size_t parts = static_cast<std::size_t>(pool.threads());
  std::vector<std::size_t> first(owners + 1, 0);  // owner q's ranges start at first[q]
  for (std::size_t q = 0; q < owners; ++q) {
    first[q + 1] = first[q];
    for (std::size_t p = 0; p < parts; ++p) first[q + 1] += part_list(p, q, owners).size();
  }
  m_sorted.resize(first[owners]);
  m_built_in_parts = true;
  m_part_touched.resize(parts * kHeaderPad);
  pool.for_chunks(owners, 1, [&](int part, std::size_t begin, std::size_t end) {
    std::vector<std::uint32_t>& touched = m_part_touched[static_cast<std::size_t>(part) * kHeaderPad];
    for (std::size_t q = begin; q < end; ++q) {
      touched.clear();
      for (std::size_t p = 0; p < parts; ++p)
        for (const Entry& e : part_list(p, q, owners))
          if (count_entry(e.bucket)) touched.push_back(e.bucket);
      auto cursor = static_cast<std::uint32_t>(first[q]);
      for (std::uint32_t b : touched) {
        cursor += m_buckets[b].count;
        m_buckets[b].start = cursor;  // the range's end, until filled
      }
      for (std::size_t p = parts; p-- > 0;) {
        const std::vector<Entry>& list = part_list(p, q, owners);
        for (auto e = list.rbegin(); e != list.rend(); ++e) m_sorted[--m_buckets[e->bucket].start] = e->item;
      }
    }
  });
  m_build_pass = 3;
}

void SpatialHash::build() {
  begin_build();
  build_some(std::numeric_limits<std::size_t>::max());
}

void SpatialHash::begin_build() {
  m_build_pass = 0;
  m_build_cursor = 0;
  m_build_next = 0;
}

bool SpatialHash::build_some(std::size_t max_visits) {
  // insert_all_and_build() built this epoch's table already (m_entries is
  // empty): sorting nothing would only drop its sorted items.
  if (m_built_in_parts) return true;
  // Counting sort by bucket over the entries only: a bucket's start is given
  // when its first entry is met (a bucket's start doubles as the fill cursor, so each
  // start is stored as the end of its range and rewound afterwards). Three
  // passes; the cursor says where the current one stands.
  const std::size_t n = m_entries.size();
  while (m_build_pass < 3) {
    const std::size_t end = n - m_build_cursor > max_visits ? m_build_cursor + max_visits : n;
    max_visits -= end - m_build_cursor;
    if (m_build_pass == 0) {
      for (std::size_t i = m_build_cursor; i < end; ++i) {
        Bucket& bucket = m_buckets[m_entries[i].bucket];
        if (bucket.count == 0 || bucket.stamp != m_epoch) continue;
        bucket.start = m_build_next;  // first time met in this pass: allocate
        m_build_next += bucket.count;
        bucket.stamp = m_epoch - 1;  // mark allocated; restored in pass 2
      }
    } else if (m_build_pass == 1) {
      for (std::size_t i = m_build_cursor; i < end; ++i) m_sorted[m_buckets[m_entries[i].bucket].start++] = m_entries[i].item;
    } else {
      for (std::size_t i = m_build_cursor; i < end; ++i) {
        Bucket& bucket = m_buckets[m_entries[i].bucket];
        if (bucket.stamp == m_epoch) continue;
        bucket.stamp = m_epoch;
        bucket.start -= bucket.count;  // rewind to the range's start
      }
    }
    m_build_cursor = end;
    if (m_build_cursor < n) return false;  // out of visits mid-pass
    ++m_build_pass;
    m_build_cursor = 0;
    if (m_build_pass == 1) m_sorted.resize(n);
    if (max_visits == 0 && m_build_pass < 3) return false;
  }
  return true;
}

std::size_t SpatialHash::memory_bytes() const {
  return heap_bytes(m_buckets) + heap_bytes(m_entries) + heap_bytes(m_sorted) + heap_bytes(m_part_entries) +
         heap_bytes(m_part_touched);
}

std::size_t SpatialHash::occupied_buckets() const {
  return static_cast<std::size_t>(
      std::count_if(m_buckets.begin(), m_buckets.end(), [&](const Bucket& b) { return b.stamp == m_epoch; }));
}

}  // namespace tcb
