#include "method/detection/spatial_hash.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <stdexcept>

using namespace tcb;

TEST_CASE("the paper's hash is symmetric around the origin; the mixed one is not", "[hash]") {
  // METHOD.md's example: cells (-10,-1,9) and (-10,1,-9) share a bucket.
  const std::uint64_t n = next_prime(10007);
  CHECK(hash_cell(HashFunction::Paper, -10, -1, 9) % n == hash_cell(HashFunction::Paper, -10, 1, -9) % n);
  CHECK(hash_cell(HashFunction::Mixed, -10, -1, 9) % n != hash_cell(HashFunction::Mixed, -10, 1, -9) % n);
}

TEST_CASE("hash_cell keeps its values: both functions, negative cells, the clamp's +-2^50", "[hash]") {
  // Computed outside this code base (Python integers, mod 2^64) from the
  // formulas in spatial_hash.hpp's file comment: a rewrite of the hash (its
  // parts, their incremental use) must not move any cell to another bucket,
  // or every stored bucket figure and hash-collision count changes.
  struct Case {
    std::int64_t i, j, k;
    std::uint64_t paper, mixed;
  };
  constexpr std::int64_t L = std::int64_t(1) << 50;
  const Case cases[] = {
      {0, 0, 0, 0x0000000000000000ULL, 0x0000000000000000ULL},
      {1, 2, 3, 0x0000000008C58A46ULL, 0xA745E8D6002149E8ULL},
      {-10, -1, 9, 0x0000000001EB3650ULL, 0xB84DA48114E39731ULL},
      {-10, 1, -9, 0x0000000001EB3650ULL, 0x81773DAC2F6E8B4BULL},
      {L, -L, 7, 0x2CF0000022D5FE01ULL, 0xBEA399C5A81B28A3ULL},
      {-L, L, -1, 0xD30FFFFFFB060049ULL, 0x822AE8CEF8F03D68ULL},
      {123456, -654321, 42, 0xFFFFFC3608CE8017ULL, 0xC338C63D70BD9C3BULL},
  };
  for (const Case& c : cases) {
    INFO("cell " << c.i << ", " << c.j << ", " << c.k);
    CHECK(hash_cell(HashFunction::Paper, c.i, c.j, c.k) == c.paper);
    CHECK(hash_cell(HashFunction::Mixed, c.i, c.j, c.k) == c.mixed);
  }
}

TEST_CASE("bucket occupancy near the origin: a slab of cells like a plate stack", "[hash]") {
  // 20 x 20 x 40 cells around the origin into a table of about twice as many
  // buckets: the mixed hash spreads them much better than the paper's.
  const std::uint64_t n = next_prime(2 * 20 * 20 * 40);
  for (auto [function, min_distinct] : {std::pair{HashFunction::Mixed, 0.75}, std::pair{HashFunction::Paper, 0.0}}) {
    std::set<std::uint64_t> buckets;
    for (int i = -10; i < 10; ++i)
      for (int j = 0; j < 40; ++j)
        for (int k = -10; k < 10; ++k) buckets.insert(hash_cell(function, i, j, k) % n);
    const double distinct = static_cast<double>(buckets.size()) / (20 * 20 * 40);
    INFO((function == HashFunction::Mixed ? "mixed" : "paper") << ": " << distinct << " of cells in distinct buckets");
    CHECK(distinct >= min_distinct);
  }
}

TEST_CASE("spatial hash: boxes, cells, epochs", "[hash]") {
  SpatialHash hash(0.5, next_prime(101), HashFunction::Mixed);
  hash.begin_epoch();
  CHECK(hash.insert_box(Vec3(0.1, 0.1, 0.1), Vec3(0.2, 0.2, 0.2), 7) == 1);
  CHECK(hash.insert_box(Vec3(-0.1, 0.1, 0.1), Vec3(0.6, 0.2, 0.2), 8) == 3);  // cells -1, 0, 1 in x
  hash.build();
  std::set<std::uint32_t> found;
  hash.for_each_in_cell(Vec3(0.15, 0.15, 0.15), [&](std::uint32_t id) { found.insert(id); });
  CHECK(found.count(7));
  CHECK(found.count(8));
  hash.begin_epoch();  // everything is gone, nothing was cleared
  hash.build();
  found.clear();
  hash.for_each_in_cell(Vec3(0.15, 0.15, 0.15), [&](std::uint32_t id) { found.insert(id); });
  CHECK(found.empty());
  CHECK(hash.occupied_buckets() == 0);
  CHECK(next_prime(100) == 101);
  // A box across the scene (a diverged simulation) is refused, not allocated.
  CHECK_THROWS_AS(hash.insert_box(Vec3(-1e3, -1e3, -1e3), Vec3(1e3, 1e3, 1e3), 9), HashOverflow);
  CHECK(next_prime(2) == 2);
}

TEST_CASE("spatial hash: cells_visited counts the cells for_each_range_in_box visits, and refuses what it refuses",
          "[hash]") {
  // The query's early end charges a widened query's cells without visiting
  // them: the count must be the visit's, at cell borders, across the origin,
  // at any scale, and an absurd box must throw as the visit does.
  for (const double cell : {1e-9, 0.5, 1e9})
    for (const HashFunction function : {HashFunction::Paper, HashFunction::Mixed}) {
      SpatialHash hash(cell, next_prime(101), function);
      hash.begin_epoch();
      hash.build();
      const Vec3 boxes[][2] = {{Vec3(0.1, 0.1, 0.1), Vec3(0.2, 0.2, 0.2)},
                               {Vec3(-0.1, 0.1, 0.1), Vec3(0.6, 0.2, 0.2)},
                               {Vec3(-1.0, -1.0, -1.0), Vec3(1.0, 1.0, 1.0)},  // on borders
                               {Vec3(-2.25, 0.0, 3.0), Vec3(-0.75, 0.0, 4.5)},
                               {Vec3(5.0, 5.0, 5.0), Vec3(5.0, 5.0, 5.0)}};
      for (const auto& b : boxes) {
        const Vec3 lo = cell * b[0], hi = cell * b[1];
        const std::size_t visited = hash.for_each_range_in_box(lo, hi, [](const std::uint32_t*, const std::uint32_t*) {});
        INFO("cell " << cell << ", box " << lo.transpose() << " .. " << hi.transpose());
        CHECK(hash.cells_visited(lo, hi) == visited);
        CHECK(static_cast<double>(visited) == hash.cells_of_box(lo, hi));
      }
      CHECK(hash.cells_visited(cell * Vec3(0.1, 0.1, 0.1), cell * Vec3(1.2, 0.2, 2.5)) == 6);  // 2 x 1 x 3
      const Vec3 far = Vec3::Constant(1e6 * cell);
      CHECK_THROWS_AS(hash.cells_visited(-far, far), HashOverflow);
      CHECK_THROWS_AS(hash.for_each_range_in_box(-far, far, [](const std::uint32_t*, const std::uint32_t*) {}),
                      HashOverflow);
    }
}

TEST_CASE("spatial hash: a cell size whose inverse is not finite is refused", "[hash]") {
  // 1e-310 is subnormal: its inverse overflows to inf, and cell_of(0) would
  // cast 0 x inf (NaN) to an integer.
  CHECK_THROWS_AS(SpatialHash(1e-310, 7, HashFunction::Mixed), std::invalid_argument);
  CHECK_THROWS_AS(SpatialHash(0.0, 7, HashFunction::Mixed), std::invalid_argument);
  CHECK_THROWS_AS(SpatialHash(std::numeric_limits<double>::infinity(), 7, HashFunction::Mixed), std::invalid_argument);
  // The smallest normal double still has a finite inverse (2^1022).
  const SpatialHash tiny(std::numeric_limits<double>::min(), 7, HashFunction::Mixed);
  CHECK(tiny.cell_of(0.0) == 0);
  CHECK(tiny.cell_of(std::numeric_limits<double>::min()) == 1);
}

TEST_CASE("spatial hash: every item is found in every cell it was inserted into", "[hash]") {
  // Random boxes in a small table (many bucket collisions), over several epochs.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-2.0, 2.0), size(0.0, 0.6);
  SpatialHash hash(0.25, 31, HashFunction::Paper);
  for (int epoch = 0; epoch < 3; ++epoch) {
    hash.begin_epoch();
    std::vector<std::pair<Vec3, Vec3>> boxes;
    for (std::uint32_t i = 0; i < 300; ++i) {
      const Vec3 lo(u(rng), u(rng), u(rng));
      boxes.emplace_back(lo, lo + Vec3(size(rng), size(rng), size(rng)));
      hash.insert_box(boxes.back().first, boxes.back().second, i);
    }
    hash.build();
    for (std::uint32_t i = 0; i < boxes.size(); ++i) {
      const Vec3 centre = 0.5 * (boxes[i].first + boxes[i].second);
      bool found = false;
      hash.for_each_in_cell(centre, [&](std::uint32_t id) { found |= id == i; });
      REQUIRE(found);
      std::size_t seen = 0;
      hash.for_each_in_box(boxes[i].first, boxes[i].second, [&](std::uint32_t id) { seen += id == i; });
      REQUIRE(seen >= 1);
    }
  }
}

TEST_CASE("spatial hash: cell_of is floor(x * (1 / cell size)), clamped to +-2^50; grid_coordinate compares as it", "[hash]") {
  // cell_of floors by truncation and a step down for negative non-integers; the reference
  // is std::floor, then the clamp, for edge values and a million random ones
  // of every magnitude and sign.
  constexpr double kLimit = 1125899906842624.0;  // 2^50
  for (const double cell : {0.25, 0.1, 3.0, 1e-9, 1e6}) {
    const SpatialHash hash(cell, 7, HashFunction::Mixed);
    const auto reference = [&](double x) {
      return static_cast<std::int64_t>(std::clamp(std::floor(x * (1.0 / cell)), -kLimit, kLimit));
    };
    std::vector<double> xs = {0.0, -0.0, cell, -cell, 0.5 * cell, -0.5 * cell, std::nextafter(cell, 0.0),
                              -std::nextafter(cell, 0.0), std::nextafter(-cell, 0.0), 1e-300, -1e-300,
                              std::numeric_limits<double>::denorm_min(), -std::numeric_limits<double>::denorm_min(),
                              kLimit * cell, -kLimit * cell, 4 * kLimit * cell, -4 * kLimit * cell, 1e300, -1e300,
                              std::numeric_limits<double>::max(), std::numeric_limits<double>::lowest()};
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
    std::uniform_int_distribution<int> exponent(-60, 60);
    for (int i = 0; i < 200000; ++i) xs.push_back(std::ldexp(mantissa(rng), exponent(rng)) * cell);
    for (int i = -1000; i <= 1000; ++i) xs.push_back(static_cast<double>(i) * cell);  // on cell borders
    for (const double x : xs) {
      INFO("cell " << cell << ", x " << x);
      REQUIRE(hash.cell_of(x) == reference(x));
      // The refresh's floor-free test (tet_hash_detection.hpp): against any
      // cell index c, including the clamp's, comparing grid_coordinate()
      // decides what comparing cell_of() does.
      const std::int64_t own = hash.cell_of(x);
      const std::int64_t limit = static_cast<std::int64_t>(kLimit);
      for (const std::int64_t c : {own - 1, own, own + 1, limit, -limit}) {
        if (c > limit || c < -limit) continue;
        const double g = hash.grid_coordinate(x), cd = static_cast<double>(c);
        REQUIRE((own >= c) == (g >= cd));
        REQUIRE((own <= c) == (g < cd + 1.0));
      }
    }
  }
}

TEST_CASE("spatial hash: a box goes into exactly the buckets hash_cell gives its cells", "[hash]") {
  // insert_box() steps the k term by addition instead of calling hash_cell()
  // per cell: both must name the same buckets, for both functions, on either
  // side of the origin. The set inserted into covers the reference set (every
  // cell's centre finds the item) and has its size (occupied buckets).
  const double cell = 0.5;
  const std::uint64_t n = next_prime(100003);
  for (HashFunction function : {HashFunction::Paper, HashFunction::Mixed})
    for (const Vec3& lo : {Vec3(-1.3, -0.2, -2.6), Vec3(1000.1, -733.7, 12.2), Vec3(-0.1, 0.1, -0.1)}) {
      const Vec3 hi = lo + Vec3(2.1, 1.6, 2.9);
      SpatialHash hash(cell, n, function);
      hash.begin_epoch();
      const std::size_t cells = hash.insert_box(lo, hi, 5);
      hash.build();
      std::set<std::uint64_t> reference;
      std::size_t cells_walked = 0;
      for (std::int64_t i = hash.cell_of(lo.x()); i <= hash.cell_of(hi.x()); ++i)
        for (std::int64_t j = hash.cell_of(lo.y()); j <= hash.cell_of(hi.y()); ++j)
          for (std::int64_t k = hash.cell_of(lo.z()); k <= hash.cell_of(hi.z()); ++k) {
            reference.insert(hash_cell(function, i, j, k) % n);
            ++cells_walked;
            const Vec3 centre = cell * (Vec3(double(i), double(j), double(k)) + Vec3::Constant(0.5));
            bool found = false;
            hash.for_each_in_cell(centre, [&](std::uint32_t id) { found |= id == 5; });
            REQUIRE(found);
          }
      CHECK(cells == cells_walked);
      CHECK(hash.entry_count() == cells_walked);  // an entry a cell, none lost or doubled
      CHECK(cells_walked >= 5 * 4 * 6);
      CHECK(hash.occupied_buckets() == reference.size());
    }
}

TEST_CASE("spatial hash: a bucket lists its entries in insertion order, however it was built", "[hash]") {
  // Tet queries rely on it (ascending ids: a binary search over a body's
  // block, and an early end at the smallest hit; tet_hash_detection.cpp).
  // Items are inserted in a shuffled order, so an order-keeping build and a
  // sorting one differ; built at once and in pieces of 7 visits.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0), size(0.0, 0.6);
  std::vector<std::uint32_t> order(400);
  for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  std::shuffle(order.begin(), order.end(), rng);
  std::vector<std::size_t> rank(order.size());
  for (std::size_t r = 0; r < order.size(); ++r) rank[order[r]] = r;
  for (const bool in_pieces : {false, true}) {
    SpatialHash hash(0.25, 31, HashFunction::Mixed);
    hash.begin_epoch();
    std::vector<Vec3> centres;
    for (const std::uint32_t item : order) {
      const Vec3 lo(u(rng), u(rng), u(rng));
      hash.insert_box(lo, lo + Vec3(size(rng), size(rng), size(rng)), item);
      centres.push_back(lo);
    }
    if (in_pieces) {
      hash.begin_build();
      while (!hash.build_some(7)) {}
    } else {
      hash.build();
    }
    std::size_t checked = 0;
    for (const Vec3& c : centres) {
      std::vector<std::uint32_t> visited;
      hash.for_each_in_cell(c, [&](std::uint32_t id) { visited.push_back(id); });
      const SpatialHash::Entries entries = hash.cell_entries(c);
      REQUIRE(std::vector<std::uint32_t>(entries.first, entries.last) == visited);
      for (std::size_t k = 1; k < visited.size(); ++k) REQUIRE(rank[visited[k - 1]] <= rank[visited[k]]);
      checked += visited.size();
    }
    CHECK(checked > 1000);  // many entries a bucket: the order is exercised
  }
}

namespace {

using Boxes = std::vector<std::pair<Vec3, Vec3>>;

// Both tables list the same items in the same order for every box's cells,
// and hold as many entries in as many buckets.
void require_same_table(const SpatialHash& serial, const SpatialHash& parallel, const Boxes& boxes) {
  CHECK(parallel.entry_count() == serial.entry_count());
  CHECK(parallel.occupied_buckets() == serial.occupied_buckets());
  for (const auto& [lo, hi] : boxes) {
    std::vector<std::uint32_t> a, b;
    serial.for_each_in_box(lo, hi, [&](std::uint32_t id) { a.push_back(id); });
    parallel.for_each_in_box(lo, hi, [&](std::uint32_t id) { b.push_back(id); });
    REQUIRE(a == b);
  }
}

}  // namespace

TEST_CASE("spatial hash: the parallel insert and build make the serial table", "[hash][threads]") {
  // Random boxes (some skipped) in a small table with many bucket collisions,
  // over several epochs of one table: every cell's bucket lists the same
  // items in the same order as after insert_box() one by one and build(),
  // for 1, 2 and 3 threads (1: the pool runs everything on the caller), with
  // owners of at most 16384 buckets and of 4 (on one thread: one owner of
  // the 31, or 8 owners; on 2 and 3 threads both become owners of 2 or 1
  // buckets, as at least kOwnersPerThread owners a thread asks).
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-2.0, 2.0), size(0.0, 0.6);
  Boxes boxes;
  for (int i = 0; i < 500; ++i) {
    const Vec3 lo(u(rng), u(rng), u(rng));
    boxes.emplace_back(lo, lo + Vec3(size(rng), size(rng), size(rng)));
  }
  const auto skipped = [](std::size_t i) { return i % 7 == 3; };
  for (const HashFunction function : {HashFunction::Paper, HashFunction::Mixed}) {
    SpatialHash serial(0.25, 31, function);
    serial.begin_epoch();
    std::size_t serial_cells = 0;
    std::vector<std::uint64_t> serial_box_cells(boxes.size(), 0);  // each box's cells; 0 where skipped
    for (std::size_t i = 0; i < boxes.size(); ++i)
      if (!skipped(i)) {
        serial_box_cells[i] = serial.insert_box(boxes[i].first, boxes[i].second, static_cast<std::uint32_t>(i));
        serial_cells += serial_box_cells[i];
      }
    serial.build();
    for (int threads = 1; threads <= 3; ++threads)
    for (const std::size_t per_owner : {SpatialHash::kBucketsPerOwner, std::size_t(4)}) {
      WorkerPool pool(threads);
      SpatialHash parallel(0.25, 31, function);
      for (int epoch = 0; epoch < 3; ++epoch) {  // later epochs start from stale stamps
        parallel.begin_epoch();
        // Each box's cells, on odd epochs (the count is optional); stale
        // values left in it must be overwritten, skipped boxes' too.
        std::vector<std::uint64_t> box_cells(boxes.size(), 12345);
        const std::size_t cells = parallel.insert_all_and_build(
            boxes.size(),
            [&](std::size_t i, Vec3& lo, Vec3& hi, std::uint32_t& item) {
              if (skipped(i)) return false;
              lo = boxes[i].first, hi = boxes[i].second, item = static_cast<std::uint32_t>(i);
              return true;
            },
            pool, per_owner, epoch % 2 == 1 ? box_cells.data() : nullptr);
        INFO("threads " << threads << ", buckets per owner " << per_owner << ", epoch " << epoch);
        CHECK(cells == serial_cells);
        if (epoch % 2 == 1) CHECK(box_cells == serial_box_cells);
        require_same_table(serial, parallel, boxes);
        // The table is built: a build afterwards (a caller's BuildOverflow
        // task) does nothing, and must not drop the sorted items.
        parallel.begin_build();
        CHECK(parallel.build_some(1));
        parallel.build();
        require_same_table(serial, parallel, boxes);
      }
    }
  }
}

TEST_CASE("spatial hash: more threads than buckets, and owners of any size, make the serial table", "[hash][threads]") {
  // A table of 2 buckets on 3 threads has fewer owners than threads (a
  // thread builds nothing); an owner size beyond any table is cut to
  // kOwnersPerThread owners a thread, or single buckets.
  Boxes boxes;
  for (int i = 0; i < 40; ++i) {
    const Vec3 lo = Vec3::Constant(0.07 * i) + Vec3(0.0, 0.3 * (i % 3), 0.0);
    boxes.emplace_back(lo, lo + Vec3::Constant(0.3));
  }
  for (const std::size_t table : {std::size_t(1), std::size_t(2), std::size_t(7)}) {
    SpatialHash serial(0.25, table, HashFunction::Mixed);
    serial.begin_epoch();
    for (std::size_t i = 0; i < boxes.size(); ++i)
      serial.insert_box(boxes[i].first, boxes[i].second, static_cast<std::uint32_t>(i));
    serial.build();
    for (const std::size_t per_owner : {std::size_t(1), std::size_t(3), std::numeric_limits<std::size_t>::max()}) {
      WorkerPool pool(3);
      SpatialHash parallel(0.25, table, HashFunction::Mixed);
      parallel.begin_epoch();
      parallel.insert_all_and_build(
          boxes.size(),
          [&](std::size_t i, Vec3& lo, Vec3& hi, std::uint32_t& item) {
            lo = boxes[i].first, hi = boxes[i].second, item = static_cast<std::uint32_t>(i);
            return true;
          },
          pool, per_owner);
      INFO("table " << table << ", buckets per owner " << per_owner);
      require_same_table(serial, parallel, boxes);
    }
  }
}

TEST_CASE("spatial hash: a parallel epoch with fewer boxes than threads keeps nothing of the last", "[hash][threads]") {
  // Parts whose range is empty never run: their lists of the last epoch
  // must not reach the new table.
  WorkerPool pool(3);
  SpatialHash hash(0.25, 31, HashFunction::Mixed);
  const auto fill = [&](std::size_t n) {
    hash.begin_epoch();
    return hash.insert_all_and_build(
        n,
        [&](std::size_t i, Vec3& lo, Vec3& hi, std::uint32_t& item) {
          lo = Vec3::Constant(0.3 * static_cast<double>(i));
          hi = lo + Vec3::Constant(0.1);
          item = static_cast<std::uint32_t>(i);
          return true;
        },
        pool);
  };
  REQUIRE(fill(30) > 0);
  CHECK(fill(1) == 1);
  CHECK(hash.entry_count() == 1);
  std::vector<std::uint32_t> met;
  for (int i = 0; i < 30; ++i) {
    const Vec3 lo = Vec3::Constant(0.3 * i);
    hash.for_each_in_box(lo, lo + Vec3::Constant(0.1), [&](std::uint32_t id) { met.push_back(id); });
  }
  std::sort(met.begin(), met.end());
  met.erase(std::unique(met.begin(), met.end()), met.end());
  CHECK(met == std::vector<std::uint32_t>{0});
}

TEST_CASE("spatial hash: the parallel insert refuses the first oversized box, as the serial one", "[hash][threads]") {
  std::vector<std::pair<Vec3, Vec3>> boxes(40, {Vec3(0, 0, 0), Vec3(0.1, 0.1, 0.1)});
  boxes[25] = {Vec3(-1e3, -1e3, -1e3), Vec3(1e3, 1e3, 1e3)};
  boxes[31] = {Vec3(-1e2, -1e2, -1e2), Vec3(1e2, 1e2, 1e2)};
  std::string serial_message;
  SpatialHash serial(0.01, 101, HashFunction::Mixed);
  serial.begin_epoch();
  try {
    for (std::size_t i = 0; i < boxes.size(); ++i) serial.insert_box(boxes[i].first, boxes[i].second, 0);
  } catch (const HashOverflow& e) {
    serial_message = e.what();
  }
  REQUIRE_FALSE(serial_message.empty());
  WorkerPool pool(3);
  SpatialHash parallel(0.01, 101, HashFunction::Mixed);
  parallel.begin_epoch();
  const auto box_of = [&](std::size_t i, Vec3& lo, Vec3& hi, std::uint32_t& item) {
    lo = boxes[i].first, hi = boxes[i].second, item = 0;
    return true;
  };
  CHECK_THROWS_WITH(parallel.insert_all_and_build(boxes.size(), box_of, pool), serial_message);
}

TEST_CASE("spatial hash: a dense grid lists exactly each cell's items in insertion order, however it is built, "
          "and nothing outside its range",
          "[hash][dense][threads]") {
  // Expected buckets counted independently: for every cell of the grid's
  // range and a shell of one cell around it, the items whose box's cell
  // range (floor of the coordinates in cells) holds the cell, in insertion
  // order (items inserted in a shuffled order). Built one by one, in pieces
  // of 7 visits, and at once on 1 to 3 threads with owners of 16384 and of
  // 4 buckets; over several epochs of one table, alternating dense grids of
  // two sizes with the hash, so stale stamps and grown buckets are met.
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> u(-1.0, 1.0), size(0.0, 0.6);
  const double cell = 0.25;
  std::vector<std::uint32_t> order(300);
  for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  std::shuffle(order.begin(), order.end(), rng);
  Boxes boxes;  // in insertion order; item order[i] has box i
  for (std::size_t i = 0; i < order.size(); ++i) {
    const Vec3 lo(u(rng), u(rng), u(rng));
    boxes.emplace_back(lo, lo + Vec3(size(rng), size(rng), size(rng)));
  }
  // Two grids holding every box: the boxes' exact extent (its cells) and a
  // wider one.
  Vec3 extent_lo = boxes[0].first, extent_hi = boxes[0].second;
  for (const auto& [lo, hi] : boxes) extent_lo = extent_lo.cwiseMin(lo), extent_hi = extent_hi.cwiseMax(hi);
  const std::pair<Vec3, Vec3> grids[] = {{extent_lo, extent_hi}, {extent_lo - Vec3(1.1, 0.3, 2.0), extent_hi + Vec3(0.6, 1.7, 0.2)}};
  const auto floor_cell = [&](double x) { return static_cast<std::int64_t>(std::floor(x * (1.0 / cell))); };
  const auto check_grid = [&](const SpatialHash& table, const std::pair<Vec3, Vec3>& grid) {
    REQUIRE(table.dense());
    std::int64_t first[3], last[3];
    for (int a = 0; a < 3; ++a) first[a] = floor_cell(grid.first[a]) - 1, last[a] = floor_cell(grid.second[a]) + 1;
    std::size_t entries = 0, cells_outside = 0;
    for (std::int64_t i = first[0]; i <= last[0]; ++i)
      for (std::int64_t j = first[1]; j <= last[1]; ++j)
        for (std::int64_t k = first[2]; k <= last[2]; ++k) {
          const bool outside = i == first[0] || i == last[0] || j == first[1] || j == last[1] || k == first[2] || k == last[2];
          std::vector<std::uint32_t> want;
          for (std::size_t n = 0; n < boxes.size(); ++n) {
            const auto& [lo, hi] = boxes[n];
            if (floor_cell(lo.x()) <= i && i <= floor_cell(hi.x()) && floor_cell(lo.y()) <= j && j <= floor_cell(hi.y()) &&
                floor_cell(lo.z()) <= k && k <= floor_cell(hi.z()))
              want.push_back(order[n]);
          }
          const Vec3 centre = cell * Vec3(double(i) + 0.5, double(j) + 0.5, double(k) + 0.5);
          const SpatialHash::Entries got = table.cell_entries(centre);
          INFO("cell " << i << " " << j << " " << k);
          REQUIRE(std::vector<std::uint32_t>(got.first, got.last) == want);
          entries += want.size();
          cells_outside += outside;
          if (outside) REQUIRE(got.first == got.last);
        }
    CHECK(entries == table.entry_count());  // no cell lists another cell's items
    CHECK(cells_outside > 0);
  };
  std::size_t expected_cells = 0;
  for (const auto& [lo, hi] : boxes) expected_cells += static_cast<std::size_t>(SpatialHash(cell, 1, HashFunction::Mixed).cells_of_box(lo, hi));
  for (const int way : {0, 1, 2, 3, 4}) {  // one by one, in pieces, at once on 1..3 threads
    INFO("way " << way);
    SpatialHash table(cell, 31, HashFunction::Mixed);
    for (int epoch = 0; epoch < 5; ++epoch) {
      INFO("epoch " << epoch);
      if (epoch == 2) {  // a hashed epoch between two dense ones
        table.begin_epoch();
        CHECK_FALSE(table.dense());
        for (std::size_t n = 0; n < boxes.size(); ++n) table.insert_box(boxes[n].first, boxes[n].second, order[n]);
        table.build();
        continue;
      }
      const auto& grid = grids[epoch % 2];
      REQUIRE(table.begin_epoch_dense(grid.first, grid.second, 100000));
      std::size_t cells = 0;
      if (way <= 1) {
        for (std::size_t n = 0; n < boxes.size(); ++n) cells += table.insert_box(boxes[n].first, boxes[n].second, order[n]);
        table.begin_build();
        while (!table.build_some(way == 0 ? std::numeric_limits<std::size_t>::max() : 7)) {}
      } else {
        WorkerPool pool(way - 1);
        cells = table.insert_all_and_build(
            boxes.size(),
            [&](std::size_t n, Vec3& lo, Vec3& hi, std::uint32_t& item) {
              lo = boxes[n].first, hi = boxes[n].second, item = order[n];
              return true;
            },
            pool, epoch == 3 ? std::size_t(4) : SpatialHash::kBucketsPerOwner);
      }
      CHECK(cells == expected_cells);
      check_grid(table, grid);
    }
  }
}

TEST_CASE("spatial hash: a dense grid too large or not finite is refused and the table hashes; a box outside the "
          "grid is refused; a search reaching outside counts every cell and visits the inside ones",
          "[hash][dense][threads]") {
  SpatialHash table(0.5, 31, HashFunction::Mixed);
  // [0, 2]^3 spans cells 0..4 on each axis: 125 cells.
  CHECK(table.begin_epoch_dense(Vec3(0, 0, 0), Vec3(2, 2, 2), 125));
  CHECK(table.dense());
  CHECK(table.table_size() == 31);  // the hash's size, which an overflow made to match takes
  CHECK_FALSE(table.begin_epoch_dense(Vec3(0, 0, 0), Vec3(2, 2, 2), 124));
  CHECK_FALSE(table.dense());
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  CHECK_FALSE(table.begin_epoch_dense(Vec3(0, nan, 0), Vec3(2, 2, 2), 1000));
  CHECK_FALSE(table.begin_epoch_dense(Vec3(0, 0, 0), Vec3(2, 2, inf), 1000));
  CHECK_FALSE(table.begin_epoch_dense(Vec3(0, 0, 0), Vec3(2, -1, 2), 1000));  // an empty box
  CHECK_FALSE(table.dense());
  // Refused: the table hashes, and takes a box anywhere.
  CHECK(table.insert_box(Vec3(5, 5, 5), Vec3(5.1, 5.1, 5.1), 7) == 1);
  table.build();
  std::vector<std::uint32_t> seen;
  table.for_each_in_cell(Vec3(5.05, 5.05, 5.05), [&](std::uint32_t id) { seen.push_back(id); });
  CHECK(seen == std::vector<std::uint32_t>{7});

  REQUIRE(table.begin_epoch_dense(Vec3(0, 0, 0), Vec3(2, 2, 2), 125));
  CHECK_THROWS_AS(table.insert_box(Vec3(1, 1, 1), Vec3(1.2, 2.6, 1.2), 1), std::logic_error);
  CHECK_THROWS_AS(table.insert_box(Vec3(-0.1, 1, 1), Vec3(1, 1, 1), 1), std::logic_error);
  REQUIRE(table.begin_epoch_dense(Vec3(0, 0, 0), Vec3(2, 2, 2), 125));
  WorkerPool pool(2);
  const auto outside = [](std::size_t n, Vec3& lo, Vec3& hi, std::uint32_t& item) {
    lo = Vec3(0.1, 0.1, 0.1) * double(n), hi = lo, item = static_cast<std::uint32_t>(n);  // n = 25: x = 2.5, cell 5
    return true;
  };
  CHECK_THROWS_AS(table.insert_all_and_build(26, outside, pool), std::logic_error);

  REQUIRE(table.begin_epoch_dense(Vec3(0, 0, 0), Vec3(2, 2, 2), 125));
  table.insert_box(Vec3(0, 0, 0), Vec3(2, 2, 2), 3);  // every cell
  table.build();
  // From cell -2 to 1 on x, 0 on y and z: 4 cells counted, 2 inside.
  std::size_t ranges = 0;
  CHECK(table.for_each_range_in_box(Vec3(-0.9, 0.1, 0.1), Vec3(0.6, 0.1, 0.1), [&](const std::uint32_t* first, const std::uint32_t* last) {
    CHECK(last - first == 1);
    CHECK(*first == 3);
    ++ranges;
  }) == 4);
  CHECK(ranges == 2);
  CHECK(table.cells_visited(Vec3(-0.9, 0.1, 0.1), Vec3(0.6, 0.1, 0.1)) == 4);
  const SpatialHash::Entries below = table.cell_entries(Vec3(-0.1, 1, 1));
  const SpatialHash::Entries above = table.cell_entries(Vec3(1, 1, 2.5));
  CHECK(below.first == below.last);
  CHECK(above.first == above.last);
}

TEST_CASE("spatial hash: an entry the caller's keep refuses is left out and its cell still counted, on any thread "
          "count; grid_cell names the bucket a point's cell reads",
          "[hash][dense][threads]") {
  // Random boxes in a dense grid, inserted at once with a keep that refuses
  // about a third of the entries by item and bucket (the bucket it is given
  // must be the one the entry goes to). Each cell must list exactly the
  // items of the table built without keep whose entry keep accepts for the
  // bucket grid_cell gives the cell's centre, in the same order; the cells
  // counted, and each box's, as without keep; on 1 to 3 threads, with
  // owners of 16384 and of 4 buckets. A few large boxes (5 to 7 cells an
  // axis) keep more cells than one of the insert's batches holds. Outside
  // the grid, and in a table that hashes, grid_cell is kOutsideGrid.
  std::mt19937 rng(29);
  std::uniform_real_distribution<double> u(-1.0, 1.0), size(0.0, 0.6), large(1.2, 1.7);
  const double cell = 0.25;
  Boxes boxes;
  for (int i = 0; i < 308; ++i) {
    const Vec3 lo(u(rng), u(rng), u(rng));
    if (i % 40 == 7)
      boxes.emplace_back(lo, lo + Vec3(large(rng), large(rng), large(rng)));
    else
      boxes.emplace_back(lo, lo + Vec3(size(rng), size(rng), size(rng)));
  }
  Vec3 grid_lo = boxes[0].first, grid_hi = boxes[0].second;
  for (const auto& [lo, hi] : boxes) grid_lo = grid_lo.cwiseMin(lo), grid_hi = grid_hi.cwiseMax(hi);
  const auto box_of = [&](std::size_t i, Vec3& lo, Vec3& hi, std::uint32_t& item) {
    lo = boxes[i].first, hi = boxes[i].second, item = static_cast<std::uint32_t>(i);
    return true;
  };
  const auto accepts = [](std::uint32_t item, std::size_t bucket) { return (item * 7 + bucket) % 3 != 0; };
  const auto keep = [&](std::uint32_t item) { return [=](std::uint32_t bucket) { return accepts(item, bucket); }; };
  WorkerPool one(1);
  SpatialHash whole(cell, 31, HashFunction::Mixed);
  REQUIRE(whole.begin_epoch_dense(grid_lo, grid_hi, 100000));
  std::vector<std::uint64_t> whole_box_cells(boxes.size(), 0);
  const std::size_t whole_cells = whole.insert_all_and_build(boxes.size(), box_of, one,
                                                             SpatialHash::kBucketsPerOwner, whole_box_cells.data());
  const auto floor_cell = [&](double x) { return static_cast<std::int64_t>(std::floor(x * (1.0 / cell))); };
  for (int threads = 1; threads <= 3; ++threads)
    for (const std::size_t per_owner : {SpatialHash::kBucketsPerOwner, std::size_t(4)}) {
      INFO("threads " << threads << ", buckets per owner " << per_owner);
      WorkerPool pool(threads);
      SpatialHash kept(cell, 31, HashFunction::Mixed);
      REQUIRE(kept.begin_epoch_dense(grid_lo, grid_hi, 100000));
      REQUIRE(kept.grid_cells() == whole.grid_cells());
      std::vector<std::uint64_t> box_cells(boxes.size(), 12345);
      CHECK(kept.insert_all_and_build(boxes.size(), box_of, pool, per_owner, box_cells.data(), keep) == whole_cells);
      CHECK(box_cells == whole_box_cells);
      std::size_t entries = 0, refused = 0, outside = 0;
      std::set<std::size_t> buckets;
      std::vector<std::size_t> kept_of(boxes.size(), 0);  // each box's entries kept
      for (std::int64_t i = floor_cell(grid_lo.x()) - 1; i <= floor_cell(grid_hi.x()) + 1; ++i)
        for (std::int64_t j = floor_cell(grid_lo.y()) - 1; j <= floor_cell(grid_hi.y()) + 1; ++j)
          for (std::int64_t k = floor_cell(grid_lo.z()) - 1; k <= floor_cell(grid_hi.z()) + 1; ++k) {
            const Vec3 centre = cell * Vec3(double(i) + 0.5, double(j) + 0.5, double(k) + 0.5);
            const std::size_t bucket = kept.grid_cell(centre);
            const SpatialHash::Entries all = whole.cell_entries(centre), got = kept.cell_entries(centre);
            if (bucket == SpatialHash::kOutsideGrid) {
              ++outside;
              REQUIRE(got.first == got.last);
              continue;
            }
            REQUIRE(bucket < kept.grid_cells());
            CHECK(buckets.insert(bucket).second);  // one cell a bucket
            std::vector<std::uint32_t> want;
            for (const std::uint32_t* it = all.first; it != all.last; ++it)
              if (accepts(*it, bucket)) {
                want.push_back(*it);
                ++kept_of[*it];
              }
            INFO("cell " << i << " " << j << " " << k);
            REQUIRE(std::vector<std::uint32_t>(got.first, got.last) == want);
            entries += want.size();
            refused += static_cast<std::size_t>(all.last - all.first) - want.size();
          }
      CHECK(entries == kept.entry_count());
      CHECK(buckets.size() == kept.grid_cells());
      CHECK(refused > 0);
      CHECK(outside > 0);
      CHECK(*std::max_element(kept_of.begin(), kept_of.end()) > SpatialHash::kKeptBatch);
    }
  SpatialHash hashing(cell, 31, HashFunction::Mixed);
  hashing.begin_epoch();
  CHECK(hashing.grid_cells() == 0);
  CHECK(hashing.grid_cell(Vec3::Zero()) == SpatialHash::kOutsideGrid);
}
