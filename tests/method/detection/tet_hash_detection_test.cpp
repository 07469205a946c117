// The tet hash's refresh (setting rehash_stale): after the table was built at
// old positions and the bodies moved, a complete refresh makes every query
// find exactly brute force's tet at the new positions, however far the tets
// moved and in whatever pieces the refresh ran; without it the stale table
// misses points. The paper's table (no refresh) is checked against brute
// force at unchanged positions by the cross-method test.
#include "method/detection/tet_hash_detection.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "method/geometry/perturbed_predicates.hpp"
#include "method/handler/work_units.hpp"
#include "sim/parallel/worker_pool.hpp"
#include "tests/method/test_worlds.hpp"

using namespace tcb;

namespace {

using Points = std::set<std::tuple<int, int, int, int>>;  // (object, vertex, other, tet)

// Every vertex queried; `total_work`, if given, gets the queries' work.
Points query_all(const World& world, const CollisionPairs& pairs, TetHashDetector* detector,
                 std::uint64_t* total_work = nullptr) {
  Points out;
  for (std::int32_t b = 0; b < static_cast<std::int32_t>(world.bodies.size()); ++b)
    for (std::int32_t v = 0; v < static_cast<std::int32_t>(world.bodies[b].x_m.size()); ++v) {
      std::uint64_t work = 0;
      const auto hit = detector ? detector->query_point(world, pairs, b, v, work)
                                : brute_force_query_point(world, pairs, b, v, work);
      if (hit) out.insert({hit->object, hit->vertex, hit->other, hit->tet});
      if (total_work) *total_work += work;
    }
  return out;
}

// Moves every movable body: a rigid shift of `cells` cells along a diagonal,
// plus a per-vertex jitter of up to `jitter_cells` cells (a deformation).
void move_bodies(World& world, double cell_m, double cells, double jitter_cells) {
  std::uint64_t state = 12345;
  const auto uniform = [&state] {  // in [-1, 1)
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(state >> 11) / static_cast<double>(std::uint64_t(1) << 52) - 1.0;
  };
  for (std::size_t b = 0; b < world.bodies.size(); ++b) {
    Body& body = world.bodies[b];
    if (body.passive) continue;
    const Vec3 shift = cells * cell_m * Vec3(1.0, -0.7, 0.4) * (b % 2 == 0 ? 1.0 : -1.0);
    for (Vec3& x : body.x_m) x += shift + jitter_cells * cell_m * Vec3(uniform(), uniform(), uniform());
  }
}

// A tet's box at positions x: what the detector stores when it hashes or
// refreshes the tet at those positions (min and max are exact).
struct TestBox {
  Vec3 lo, hi;
};
TestBox box_at(const std::vector<Vec3>& x, const Tet& t) {
  TestBox box{x[t[0]], x[t[0]]};
  for (int k = 1; k < 4; ++k) box.lo = box.lo.cwiseMin(x[t[k]]), box.hi = box.hi.cwiseMax(x[t[k]]);
  return box;
}

// The union of body b's non-degenerate tets' boxes at its positions (empty
// for a body without a partner): what the detector's body_box(b) must be.
BoxUnion tet_box_union(const World& world, const CollisionPairs& pairs, std::size_t b) {
  BoxUnion u;
  if (!pairs.has_partner(b)) return u;
  const Body& body = world.bodies[b];
  for (std::size_t t = 0; t < body.mesh->tet_count(); ++t) {
    if (body.mesh->is_degenerate[t]) continue;
    const TestBox box = box_at(body.x_m, body.mesh->tets[t]);
    u.add_box(box.lo, box.hi);
  }
  return u;
}

// Every test scene at three separations of its movable bodies (0, 0.45 and
// 3 cells, jittered by a fifth of that): f(world, pairs, settings) with the
// bodies moved there.
template <typename F>
void for_each_scene_apart(F&& f) {
  for (const auto& [name, scene] : test::collision_scenes())
    for (const double shift_cells : {0.0, 0.45, 3.0}) {
      INFO(name << ", shift " << shift_cells << " cells");
      World world = build_world(scene);
      const CollisionPairs pairs(world);
      const DetectionSettings settings = test::settings_of(world, scene).detection;
      move_bodies(world, settings.cell_size_m, shift_cells, 0.2 * shift_cells);
      f(world, pairs, settings);
    }
}

// Every vertex's query (unwidened, or widened by margin_m) finds the same
// tet in `got` as in `want`, and is charged the same work.
void require_same_queries(const World& world, const CollisionPairs& pairs, TetHashDetector& want,
                          TetHashDetector& got, double margin_m = 0.0) {
  for (std::int32_t o = 0; o < static_cast<std::int32_t>(world.bodies.size()); ++o)
    for (std::int32_t v = 0; v < static_cast<std::int32_t>(world.bodies[o].x_m.size()); ++v) {
      std::uint64_t want_work = 0, got_work = 0;
      const auto want_hit = want.query_point(world, pairs, o, v, want_work, margin_m);
      const auto got_hit = got.query_point(world, pairs, o, v, got_work, margin_m);
      INFO("body " << o << ", vertex " << v);
      CHECK(got_work == want_work);
      REQUIRE(got_hit.has_value() == want_hit.has_value());
      if (got_hit) CHECK(std::tie(got_hit->other, got_hit->tet) == std::tie(want_hit->other, want_hit->tet));
    }
}

// The entries of a table hashed for queries at its own positions, counted
// here without it (hash_tets() header): each non-degenerate tet of a walked
// body b whose box is not strictly apart from the box around the other
// walked bodies' vertices (never apart when b collides with itself) is
// entered into each cell of its box holding a vertex of another walked body
// (of any walked body, with self-collision), where some walked body has
// under a quarter of its vertices in such cells (so not where every walked
// body collides with itself; otherwise the cells are not told apart).
// `tets_only`: the entries with only the first rule (every cell of each
// such tet's box); `told_apart`: with both rules, whether or not the cells
// are told apart. Cells cut as the table cuts them (SpatialHash::cell_of).
struct ReachableEntries {
  std::size_t tets_only = 0, told_apart = 0, cells_too = 0;
  bool tags_pay = false;  // cells are told apart (cells_too is told_apart)
};
ReachableEntries reachable_entries(const World& world, const CollisionPairs& pairs, double cell_m) {
  const SpatialHash cuts(cell_m, 1, HashFunction::Mixed);
  using Cell = std::tuple<std::int64_t, std::int64_t, std::int64_t>;
  std::map<Cell, std::set<std::size_t>> holders;  // a cell's walked bodies with a vertex in it
  const std::size_t n = world.bodies.size();
  std::vector<BoxUnion> vertex_box(n);
  for (std::size_t b = 0; b < n; ++b) {
    if (!pairs.has_partner(b)) continue;
    for (const Vec3& p : world.bodies[b].x_m) {
      holders[Cell{cuts.cell_of(p.x()), cuts.cell_of(p.y()), cuts.cell_of(p.z())}].insert(b);
      vertex_box[b].add_box(p, p);
    }
  }
  ReachableEntries out;
  bool cells_told_apart = false;
  for (std::size_t b = 0; b < n; ++b)
    cells_told_apart = cells_told_apart || (pairs.has_partner(b) && !pairs.enabled(b, b));
  for (std::size_t b = 0; b < n; ++b) {
    if (!pairs.has_partner(b)) continue;
    const bool self = pairs.enabled(b, b);
    BoxUnion others;
    for (std::size_t o = 0; o < n; ++o)
      if (o != b && pairs.has_partner(o)) others.add_union(vertex_box[o]);
    const Body& body = world.bodies[b];
    for (std::size_t t = 0; t < body.mesh->tets.size(); ++t) {
      if (body.mesh->is_degenerate[t]) continue;
      Vec3 lo = body.x_m[body.mesh->tets[t][0]], hi = lo;
      for (int k = 1; k < 4; ++k) {
        lo = lo.cwiseMin(body.x_m[body.mesh->tets[t][k]]);
        hi = hi.cwiseMax(body.x_m[body.mesh->tets[t][k]]);
      }
      if (!self && others.misses(lo, hi)) continue;
      for (std::int64_t i = cuts.cell_of(lo.x()); i <= cuts.cell_of(hi.x()); ++i)
        for (std::int64_t j = cuts.cell_of(lo.y()); j <= cuts.cell_of(hi.y()); ++j)
          for (std::int64_t k = cuts.cell_of(lo.z()); k <= cuts.cell_of(hi.z()); ++k) {
            ++out.tets_only;
            const auto it = holders.find(Cell{i, j, k});
            if (it != holders.end() && (self || it->second.size() > 1 || *it->second.begin() != b))
              ++out.told_apart;
          }
    }
  }
  // The tags pay where some walked body has under a quarter of its
  // vertices in cells holding a vertex of another walked body (any vertex,
  // so all of its own, when it collides with itself).
  bool some_body_apart = false;
  for (std::size_t b = 0; b < n; ++b) {
    if (!pairs.has_partner(b)) continue;
    std::size_t taking = 0;
    for (const Vec3& p : world.bodies[b].x_m) {
      const Cell cell{cuts.cell_of(p.x()), cuts.cell_of(p.y()), cuts.cell_of(p.z())};
      const std::set<std::size_t>& in_cell = holders.at(cell);  // b's own vertex is in it
      taking += pairs.enabled(b, b) || in_cell.size() > 1 || *in_cell.begin() != b;
    }
    some_body_apart = some_body_apart || 4 * taking < world.bodies[b].x_m.size();
  }
  out.tags_pay = cells_told_apart && some_body_apart;
  out.cells_too = out.tags_pay ? out.told_apart : out.tets_only;
  return out;
}

// On 0 to 2 threads (0: without a pool), a detector hashed for queries at
// its own positions: it must charge the work of `full` (the full table,
// hashed here with `full_work`), lay out a dense grid (every test scene's
// grid is small enough), hold exactly the entries reachable_entries()
// counts, by the model's choice of rule, and answer and charge every query
// as `full` does; then check(reached, want) checks the rest.
template <typename Check>
void check_reached(const World& world, const CollisionPairs& pairs, const DetectionSettings& settings,
                   TetHashDetector& full, std::uint64_t full_work, Check&& check) {
  const ReachableEntries want = reachable_entries(world, pairs, settings.cell_size_m);
  for (const int threads : {0, 1, 2}) {
    INFO(threads << " threads");
    WorkerPool pool(std::max(threads, 1));
    TetHashDetector reached(world, settings);
    CHECK(reached.hash_tets(world, pairs, threads > 0 ? &pool : nullptr, true) == full_work);
    REQUIRE(reached.hash().dense());
    CHECK(reached.hash().entry_count() == want.cells_too);
    CHECK(reached.cells_told_apart() == want.tags_pay);
    require_same_queries(world, pairs, full, reached);
    check(reached, want);
  }
}

std::uint64_t refresh(const World& world, const CollisionPairs& pairs, TetHashDetector& detector,
                      std::size_t per_task) {
  detector.begin_refresh();
  std::uint64_t work = 0;
  for (bool done = false; !done;) work += detector.refresh_some_tets(world, pairs, per_task, done);
  detector.mutable_overflow().begin_build();
  while (!detector.mutable_overflow().build_some(3)) {
  }
  return work;
}

}  // namespace

TEST_CASE("a refreshed tet hash finds exactly brute force's points after any motion; the stale one misses some",
          "[detection][rehash]") {
  struct Motion {
    double cells, jitter_cells;
  };
  for (const auto& [name, scene] : test::collision_scenes())
    for (const Motion m : {Motion{0.0, 0.0}, Motion{0.45, 0.0}, Motion{2.3, 0.0}, Motion{0.3, 0.6}, Motion{3.0, 1.5}})
      for (const std::size_t per_task : {std::size_t{1}, std::size_t{7}, std::numeric_limits<std::size_t>::max()}) {
        INFO(name << ", shift " << m.cells << " cells, jitter " << m.jitter_cells << ", " << per_task << " a task");
        World world = build_world(scene);
        const CollisionSettings settings = test::settings_of(world, scene);
        const CollisionPairs pairs(world);
        TetHashDetector detector(world, settings.detection);
        detector.enable_refresh();
        detector.hash_tets(world, pairs);
        move_bodies(world, settings.detection.cell_size_m, m.cells, m.jitter_cells);
        const Points truth = query_all(world, pairs, nullptr);
        const Points stale = query_all(world, pairs, &detector);
        // What the stale table finds is inside (its tet is tested at the
        // current positions), though under deformation perhaps not in the
        // smallest tet that holds it: that one may be hashed elsewhere.
        std::set<std::pair<int, int>> inside;
        for (const auto& p : truth) inside.insert({std::get<0>(p), std::get<1>(p)});
        for (const auto& p : stale) CHECK(inside.count({std::get<0>(p), std::get<1>(p)}) == 1);
        const std::uint64_t charged = refresh(world, pairs, detector, per_task);
        CHECK(query_all(world, pairs, &detector) == truth);
        if (m.cells == 0.0 && m.jitter_cells == 0.0) {
          CHECK(detector.overflow_tets() == 0);  // nothing left its cells
          CHECK(stale == truth);
        } else {
          CHECK(detector.overflow_tets() > 0);
          CHECK(charged > detector.overflow_tets());  // a unit a tet revisited, plus its overflow cells
        }
        if (m.cells >= 2.0 && !truth.empty()) CHECK(stale != truth);  // the refresh had something to find
      }
}

TEST_CASE("the whole refresh at once, on 1 or 2 threads, is the piecewise refresh: same overflow, work and answers",
          "[detection][rehash][threads]") {
  for (const auto& [name, scene] : test::collision_scenes())
    for (const double jitter : {0.0, 0.3, 1.5}) {
      INFO(name << ", jitter " << jitter << " cells");
      World world = build_world(scene);
      const CollisionSettings settings = test::settings_of(world, scene);
      const CollisionPairs pairs(world);
      const World at_hash = build_world(scene);  // the positions the detectors hash
      move_bodies(world, settings.detection.cell_size_m, 0.2, jitter);
      // Each detector hashed at the old positions, then refreshed at the new.
      const auto hashed = [&] {
        TetHashDetector d(at_hash, settings.detection);
        d.enable_refresh();
        d.hash_tets(at_hash, pairs);
        return d;
      };
      TetHashDetector piecewise = hashed();
      const std::uint64_t piecewise_work = refresh(world, pairs, piecewise, 5);
      std::uint64_t piecewise_query_work = 0;  // decided by the stored boxes too
      const Points answers = query_all(world, pairs, &piecewise, &piecewise_query_work);
      CHECK(answers == query_all(world, pairs, nullptr));
      for (const int threads : {1, 2}) {
        INFO("threads " << threads);
        WorkerPool pool(threads);
        TetHashDetector whole = hashed();
        CHECK(whole.refresh_tets(world, pairs, &pool) == piecewise_work);
        whole.mutable_overflow().build();
        CHECK(whole.overflow_tets() == piecewise.overflow_tets());
        std::uint64_t query_work = 0;
        CHECK(query_all(world, pairs, &whole, &query_work) == answers);
        CHECK(query_work == piecewise_query_work);
      }
      if (jitter > 0.0) CHECK(piecewise.overflow_tets() > 0);
    }
}

TEST_CASE("a tet whose box reaches the next cell's border has left its cells; one at its own cell's border has not; one past it has",
          "[detection][rehash]") {
  // Cell borders decide the refresh exactly: cell_of(x) = floor(x / cell),
  // so a box's top exactly on the border above its top cell is in the next
  // cell, and its bottom exactly on its bottom cell's lower border is still
  // in that cell. A power-of-two cell makes the grid coordinates exact, so
  // the moved vertices sit exactly on the borders. Both refresh paths.
  const test::TestScene scene = test::collision_scenes()[3].second;  // a passive floor and a cube
  World world = build_world(scene);
  CollisionSettings settings = test::settings_of(world, scene);
  settings.detection.cell_size_m = std::exp2(std::round(std::log2(settings.detection.cell_size_m)));
  const double cell = settings.detection.cell_size_m;
  const CollisionPairs pairs(world);
  // The cube off the grid's borders (it starts on one): both moves below
  // then change the positions.
  const auto start = [&] {
    World w = build_world(scene);
    for (Vec3& v : w.bodies[1].x_m) v.x() += 0.3 * cell;
    return w;
  };
  world = start();
  std::vector<Vec3>& x = world.bodies[1].x_m;
  double min_x = x[0].x(), max_x = x[0].x();
  for (const Vec3& v : x) {
    min_x = std::min(min_x, v.x());
    max_x = std::max(max_x, v.x());
  }
  const TetMesh& mesh = *world.bodies[1].mesh;
  const auto tets_with_vertex_at = [&](double at) {
    std::size_t n = 0;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
      bool has = false;
      for (const std::int32_t v : mesh.tets[t]) has = has || x[static_cast<std::size_t>(v)].x() == at;
      n += !mesh.is_degenerate[t] && has;
    }
    return n;
  };
  const std::size_t top_tets = tets_with_vertex_at(max_x), bottom_tets = tets_with_vertex_at(min_x);
  REQUIRE(top_tets > 0);
  REQUIRE(bottom_tets > 0);
  // The top vertices to the border above their cell (into the next cell),
  // or the bottom ones down to the border below theirs (the same cell), or
  // half a cell past it (the cell below); no other vertex moves.
  struct Move {
    const char* name;
    double from, to;
    std::size_t left;  // the tets expected in the overflow
  };
  const double top_border = (std::floor(max_x / cell) + 1.0) * cell, bottom_border = std::floor(min_x / cell) * cell;
  for (const Move& m : {Move{"top to the next cell's border", max_x, top_border, top_tets},
                        Move{"bottom to its own cell's border", min_x, bottom_border, 0},
                        Move{"bottom into the cell below", min_x, bottom_border - 0.5 * cell, bottom_tets}}) {
    for (const bool at_once : {false, true}) {
      INFO(m.name << (at_once ? ", at once" : ", in pieces"));
      World moved = start();
      TetHashDetector detector(moved, settings.detection);
      detector.enable_refresh();
      detector.hash_tets(moved, pairs);
      REQUIRE(m.to != m.from);
      for (Vec3& v : moved.bodies[1].x_m)
        if (v.x() == m.from) v.x() = m.to;
      if (at_once) detector.refresh_tets(moved, pairs, nullptr);
      else refresh(moved, pairs, detector, 5);
      CHECK(detector.overflow_tets() == m.left);
      CHECK(query_all(moved, pairs, &detector) == query_all(moved, pairs, nullptr));
    }
  }
}

TEST_CASE("a world whose bodies, position counts or tet counts differ from the detector's meshes is refused",
          "[detection]") {
  // The tag pass writes a cell a position into arrays laid out for the
  // meshes' vertices (a body with more positions would write past them),
  // and the walks find a body's tets in the detector's layout.
  const test::TestScene scene = test::collision_scenes()[3].second;  // a passive floor and a cube
  const World world = build_world(scene);
  const CollisionSettings settings = test::settings_of(world, scene);
  const CollisionPairs pairs(world);
  TetHashDetector tagged(world, settings.detection);  // hashes for its own positions, with the tag pass
  TetHashDetector kept(world, settings.detection);    // keeps its cells for refreshes (no tags)
  kept.enable_refresh();
  tagged.hash_tets(world, pairs, nullptr, true);
  REQUIRE(tagged.cells_told_apart());  // the tag pass ran: the path the check guards
  kept.hash_tets(world, pairs);
  const auto refused = [&](const World& odd) {
    CHECK_THROWS_AS(tagged.hash_tets(odd, pairs, nullptr, true), std::invalid_argument);
    CHECK_THROWS_AS(kept.hash_tets(odd, pairs), std::invalid_argument);
    CHECK_THROWS_AS(kept.refresh_tets(odd, pairs, nullptr), std::invalid_argument);
    bool done = false;
    kept.begin_refresh();
    CHECK_THROWS_AS(kept.refresh_some_tets(odd, pairs, 1, done), std::invalid_argument);
    kept.begin_hash();
    CHECK_THROWS_AS(kept.hash_some_tets(odd, pairs, 1, done), std::invalid_argument);
  };
  for (const int extra : {1, -1}) {
    INFO("positions " << extra);
    World odd = clone_world(world);
    if (extra > 0) odd.bodies[1].x_m.push_back(odd.bodies[1].x_m.back());
    else odd.bodies[1].x_m.pop_back();
    refused(odd);
  }
  {
    INFO("one tet fewer, the same vertices");
    World odd = clone_world(world);
    auto mesh = std::make_shared<TetMesh>(*odd.bodies[1].mesh);
    mesh->tets.pop_back();
    mesh->is_degenerate.pop_back();
    odd.bodies[1].mesh = mesh;
    refused(odd);
  }
  {
    INFO("one body fewer");
    World odd = clone_world(world);
    odd.bodies.pop_back();
    refused(odd);
  }
  // Both still serve their own world, each query as brute force answers it.
  tagged.hash_tets(world, pairs, nullptr, true);
  kept.hash_tets(world, pairs);
  const Points truth = query_all(world, pairs, nullptr);
  CHECK(query_all(world, pairs, &tagged) == truth);
  CHECK(query_all(world, pairs, &kept) == truth);
}

TEST_CASE("a new hash drops the overflow; fixed passive bodies are never revisited", "[detection][rehash]") {
  const test::TestScene scene = test::collision_scenes()[3].second;  // a passive floor and a cube
  World world = build_world(scene);
  REQUIRE(world.bodies[0].passive);
  const CollisionSettings settings = test::settings_of(world, scene);
  const CollisionPairs pairs(world);
  TetHashDetector detector(world, settings.detection);
  detector.enable_refresh();
  detector.hash_tets(world, pairs);
  move_bodies(world, settings.detection.cell_size_m, 1.5, 0.0);
  const std::uint64_t charged = refresh(world, pairs, detector, 5);
  std::uint64_t cube_tets = 0;
  for (const char d : world.bodies[1].mesh->is_degenerate) cube_tets += d ? 0 : 1;
  CHECK(charged == cube_tets * work::kTetBox + [&] {  // the floor's tets cost nothing
          std::uint64_t cells = 0;
          SpatialHash count(settings.detection.cell_size_m, 101, settings.detection.hash);
          for (std::size_t i = 0; i < world.bodies[1].mesh->tets.size(); ++i) {
            if (world.bodies[1].mesh->is_degenerate[i]) continue;
            const TestBox box = box_at(world.bodies[1].x_m, world.bodies[1].mesh->tets[i]);
            cells += count.insert_box(box.lo, box.hi, 0);
          }
          return cells;
        }());  // 1.5 cells along every axis: every cube tet left its cells
  CHECK(detector.overflow_tets() == cube_tets);
  detector.hash_tets(world, pairs);
  CHECK(detector.overflow_tets() == 0);
  CHECK(query_all(world, pairs, &detector) == query_all(world, pairs, nullptr));
}

TEST_CASE("hashing the tets on 1, 2 or 3 threads gives the piecewise table: same work, answers and refresh",
          "[detection][threads]") {
  // Every test scene (passive floors, bodies without partners, degenerate
  // tets): each vertex's answer and work units agree with the table the
  // fine tasks build (insert_box() a tet, then a build), and so does a
  // refresh after motion, which reads the cells the whole-stage hash
  // recorded. Threads 0: hash_tets() without a pool.
  for (const auto& [name, scene] : test::collision_scenes())
    for (const int threads : {0, 1, 2, 3}) {
      INFO(name << ", " << threads << " threads");
      World world = build_world(scene);
      const CollisionSettings settings = test::settings_of(world, scene);
      const CollisionPairs pairs(world);
      TetHashDetector serial(world, settings.detection), parallel(world, settings.detection);
      serial.enable_refresh();
      parallel.enable_refresh();
      WorkerPool pool(std::max(threads, 1));
      serial.begin_hash();
      bool done = false;
      const std::uint64_t serial_work =
          serial.hash_some_tets(world, pairs, std::numeric_limits<std::size_t>::max(), done);
      REQUIRE(done);
      serial.mutable_hash().build();
      CHECK(parallel.hash_tets(world, pairs, threads > 0 ? &pool : nullptr) == serial_work);
      CHECK(parallel.hash().entry_count() == serial.hash().entry_count());
      const auto each_answer = [&](TetHashDetector& detector) {
        std::vector<std::tuple<int, int, std::uint64_t>> out;  // (other, tet, work) per vertex
        for (std::int32_t b = 0; b < static_cast<std::int32_t>(world.bodies.size()); ++b)
          for (std::int32_t v = 0; v < static_cast<std::int32_t>(world.bodies[b].x_m.size()); ++v) {
            std::uint64_t work = 0;
            const auto hit = detector.query_point(world, pairs, b, v, work);
            out.emplace_back(hit ? hit->other : -1, hit ? hit->tet : -1, work);
          }
        return out;
      };
      CHECK(each_answer(parallel) == each_answer(serial));
      move_bodies(world, settings.detection.cell_size_m, 0.8, 0.3);
      CHECK(refresh(world, pairs, parallel, 7) == refresh(world, pairs, serial, 7));
      CHECK(parallel.overflow_tets() == serial.overflow_tets());
      CHECK(each_answer(parallel) == each_answer(serial));
    }
}

TEST_CASE("a tet met several times in a query's bucket is one candidate", "[detection]") {
  // A table of one bucket: every cell of every tet lands in it, each tet's
  // entries side by side, in slot order (the detector's Morton layout). A
  // query is charged one candidate for each distinct tet of the other body
  // whose box holds the point, up to the first in file order that holds the
  // point itself (later ids are skipped: the lowest one
  // is the answer), however many cells the tet covers. Small cells make each
  // tet cover many.
  const auto scene = test::scene_of({{"a", "box:size=0.2x0.2x0.2,cells=2x2x2"},
                                     {"b", "box:size=0.2x0.2x0.2,cells=2x2x2", Vec3(0.05, 0.05, 0.05)}});
  const World world = test::build_world(scene);
  const CollisionPairs pairs(world);
  DetectionSettings settings;
  settings.cell_size_m = 0.02;  // a tet of 0.1 m spans ~6 cells an axis
  settings.table_size = 1;
  TetHashDetector detector(world, settings);
  detector.hash_tets(world, pairs);
  int checked = 0;
  for (std::int32_t v = 0; v < static_cast<std::int32_t>(world.bodies[0].x_m.size()); ++v) {
    const Vec3& p = world.bodies[0].x_m[v];
    std::uint64_t expected = work::kPointQuery;
    const Body& b = world.bodies[1];
    std::optional<std::size_t> inside;
    for (std::size_t i = 0; i < b.mesh->tets.size() && !inside; ++i) {
      const Tet& t = b.mesh->tets[i];
      const TestBox box = box_at(b.x_m, t);
      if ((p.array() < box.lo.array()).any() || (p.array() > box.hi.array()).any()) continue;
      expected += work::kCandidate;
      if (point_in_tet_perturbed(p, b.x_m[t[0]], b.x_m[t[1]], b.x_m[t[2]], b.x_m[t[3]])) inside = i;
    }
    std::uint64_t work = 0;
    const auto hit = detector.query_point(world, pairs, 0, v, work);
    INFO("vertex " << v);
    CHECK(work == expected);
    CHECK(hit.has_value() == inside.has_value());
    if (hit && inside) CHECK(hit->tet == static_cast<std::int32_t>(*inside));
    checked += expected > work::kPointQuery + work::kCandidate;  // a tet charged once though met in many cells
  }
  CHECK(checked > 3);
}

TEST_CASE("a query is charged a unit and a candidate for each tet of an enabled body whose stored box holds the point, "
          "before and after motion and after a refresh, in every scene",
          "[detection]") {
  // The work of a query counted independently: with a table of one bucket
  // every hashed tet is in the point's bucket, so a query is charged one
  // unit, and one candidate for each tet of an enabled body (not incident to
  // the point) whose stored box holds it, in id order up to the first that
  // holds the point at the current positions. After a refresh that filled
  // the overflow (a table of one bucket too, holding tets the main one
  // already lists) a unit more for its cell, and the boxes are the current
  // ones. The query's first test (a point outside every other body's stored
  // boxes ends at once) must change none of this: a union too small would
  // charge less, one of the current positions instead of the stored boxes
  // would too, once the bodies moved, and so would an early end that forgot
  // the overflow's unit; with self-collision it must not reject at all.
  for (const auto& [name, scene] : test::collision_scenes())
    for (const double shift_cells : {0.0, 0.45, 3.0}) {
      INFO(name << ", shift " << shift_cells << " cells");
      World world = build_world(scene);
      const CollisionPairs pairs(world);
      DetectionSettings settings = test::settings_of(world, scene).detection;
      settings.table_size = 1;
      TetHashDetector detector(world, settings);
      detector.enable_refresh();
      detector.hash_tets(world, pairs);
      std::vector<std::vector<Vec3>> stored_at;  // positions the boxes were stored at
      for (const Body& b : world.bodies) stored_at.push_back(b.x_m);
      move_bodies(world, settings.cell_size_m, shift_cells, 0.2 * shift_cells);
      // margin_m > 0: the widened query, every box grown by the margin as the
      // query grows it, and a unit for each cell within the margin of p (in
      // each table searched).
      const auto check_every_query = [&](double margin_m, bool overflow, int& without_candidates, int& charged) {
        const Vec3 grow = Vec3::Constant(margin_m);
        for (std::int32_t o = 0; o < static_cast<std::int32_t>(world.bodies.size()); ++o)
          for (std::int32_t v = 0; v < static_cast<std::int32_t>(world.bodies[o].x_m.size()); ++v) {
            const Vec3& p = world.bodies[o].x_m[v];
            std::uint64_t candidates = 0;
            bool found = false;
            for (std::size_t b = 0; b < world.bodies.size() && !found; ++b) {
              if (!pairs.enabled(o, b)) continue;
              const Body& body = world.bodies[b];
              for (std::size_t t = 0; t < body.mesh->tet_count() && !found; ++t) {
                const Tet& tet = body.mesh->tets[t];
                if (body.mesh->is_degenerate[t]) continue;
                if (b == static_cast<std::size_t>(o) && std::count(tet.begin(), tet.end(), v) > 0) continue;
                const TestBox box = box_at(stored_at[b], tet);
                const Vec3 lo = box.lo - grow, hi = box.hi + grow;
                if ((p.array() < lo.array()).any() || (p.array() > hi.array()).any()) continue;
                candidates += work::kCandidate;
                const auto& x = body.x_m;
                found = point_in_tet_perturbed(p, x[tet[0]], x[tet[1]], x[tet[2]], x[tet[3]]);
              }
            }
            const auto cells = static_cast<std::uint64_t>(
                margin_m > 0.0 ? detector.mutable_hash().cells_of_box(p - grow, p + grow) : 1.0);
            std::uint64_t work = 0;
            const auto hit = detector.query_point(world, pairs, o, v, work, margin_m);
            INFO("body " << o << ", vertex " << v << ", margin " << margin_m);
            CHECK(work == work::kPointQuery * cells * (overflow ? 2 : 1) + candidates);
            CHECK(hit.has_value() == found);
            without_candidates += candidates == 0;
            charged += candidates > 0;
          }
      };
      // Both kinds of point must occur, or the test checks one path only:
      // at rest every scene has points charged candidates; three cells
      // apart, points in no other body's tet box (those the first test may
      // reject; whether it does is not visible here, only that the work
      // stays the scan's). Margins: the paper's query, and widened ones
      // reaching into the next cell.
      const double cell_m = settings.cell_size_m;
      for (const double margin_m : {0.0, 0.3 * cell_m}) {
        int without_candidates = 0, charged = 0;
        check_every_query(margin_m, false, without_candidates, charged);
        if (shift_cells == 0.0) CHECK(charged > 0);
        if (shift_cells == 3.0) CHECK(without_candidates > 0);
      }
      // Refreshed: every box stored at the current positions (fixed passive
      // bodies did not move), the overflow searched too once it holds tets.
      detector.refresh_tets(world, pairs);
      for (std::size_t b = 0; b < world.bodies.size(); ++b) stored_at[b] = world.bodies[b].x_m;
      if (shift_cells > 0.0) CHECK(detector.overflow_tets() > 0);
      for (const double margin_m : {0.0, 0.3 * cell_m}) {
        int without_candidates = 0, charged = 0;
        check_every_query(margin_m, detector.overflow_tets() > 0, without_candidates, charged);
        if (shift_cells == 0.0) CHECK(charged > 0);
      }
    }
}

TEST_CASE("every hashing and refresh path keeps each body's box union exactly the union of its stored boxes",
          "[detection][threads]") {
  // The query's first test rejects a point outside the other bodies'
  // unions, so a union a tet short would lose that tet's candidates. Each
  // body's union must be exactly the one of its non-degenerate tets' boxes
  // at the positions they were stored (empty for a body without a partner),
  // after the piecewise hash (pieces of 7 tets, across bodies), the
  // whole-stage hash on 0 to 3 threads, and either refresh after motion
  // (which leaves the fixed passive bodies' unions from the hash).
  const auto check_unions = [&](const World& world, const CollisionPairs& pairs, const TetHashDetector& detector) {
    for (std::size_t b = 0; b < world.bodies.size(); ++b) {
      INFO("body " << b);
      const BoxUnion want = tet_box_union(world, pairs, b);
      CHECK(detector.body_box(b).lo == want.lo);
      CHECK(detector.body_box(b).hi == want.hi);
      CHECK_FALSE(detector.body_box(b).poisoned());
    }
  };
  for (const auto& [name, scene] : test::collision_scenes())
    for (const int threads : {-1, 0, 1, 2, 3}) {  // -1: the piecewise hash
      INFO(name << ", " << threads << " threads");
      World world = build_world(scene);
      const CollisionSettings settings = test::settings_of(world, scene);
      const CollisionPairs pairs(world);
      TetHashDetector detector(world, settings.detection);
      detector.enable_refresh();
      WorkerPool pool(std::max(threads, 1));
      if (threads < 0) {
        detector.begin_hash();
        for (bool done = false; !done;) detector.hash_some_tets(world, pairs, 7, done);
        detector.mutable_hash().build();
      } else {
        detector.hash_tets(world, pairs, threads > 0 ? &pool : nullptr);
      }
      check_unions(world, pairs, detector);
      move_bodies(world, settings.detection.cell_size_m, 0.8, 0.3);
      if (threads < 0)
        refresh(world, pairs, detector, 7);
      else
        detector.refresh_tets(world, pairs, threads > 0 ? &pool : nullptr);
      check_unions(world, pairs, detector);
    }
}

TEST_CASE("a hash made for queries at its own positions leaves out the tets no query point reaches, and every query "
          "finds and is charged what it would with them in",
          "[detection][threads]") {
  // hash_tets(..., queries_at_these_positions = true) skips a tet strictly
  // apart from the box around the other walked bodies' vertices, and, in a
  // dense grid, enters the others only into cells where a vertex of another
  // walked body lies, where some body has under a quarter of its vertices
  // in such cells (cells_told_apart(), which must be the model's choice;
  // both choices must occur, the second where telling cells apart would
  // have left entries out). Every vertex's
  // query must give the same contact and work as with the full table, the
  // hash the same work, on 0 to 2 threads; the table must hold exactly the
  // entries reachable_entries() counts, fewer than the tet rule alone
  // somewhere (or the test checks nothing), and nothing may be
  // left out once refreshing is enabled (a refreshed table serves later
  // positions). A self-colliding body's tets, which its own vertices query,
  // must all stay in: the folded pair's own queries check that, and so do
  // the scenes again with every active body colliding with itself (then,
  // where no passive body is walked, the cells are not told apart: the
  // all-self exit, which some scene with every walked body self-colliding
  // must show). One detector hashed again after
  // the bodies moved (its grid and tags made anew) must hold exactly the
  // new positions' entries: a tag left from the last hash would add some.
  bool some_skipped = false, some_cells_left_out = false, some_all_self = false, some_dense_again = false;
  bool some_unmade = false, some_told_apart = false, some_declined = false;
  for_each_scene_apart([&](World& world, const CollisionPairs& pairs, const DetectionSettings& settings) {
    TetHashDetector full(world, settings);
    const std::uint64_t full_work = full.hash_tets(world, pairs);
    check_reached(world, pairs, settings, full, full_work, [&](const TetHashDetector& reached,
                                                               const ReachableEntries& want) {
      some_told_apart = some_told_apart || want.tags_pay;
      some_declined = some_declined || (!want.tags_pay && want.told_apart < want.tets_only);
      some_skipped = some_skipped || want.tets_only < full.hash().entry_count();
      some_cells_left_out = some_cells_left_out || want.cells_too < want.tets_only;
      // Some tets left out before their boxes were made (the shortcut the
      // checks here and below must cover), and none by the full table.
      some_unmade = some_unmade || reached.tets_unmade() > 0;
      CHECK(full.tets_unmade() == 0);
      for (std::size_t b = 0; b < world.bodies.size(); ++b) {
        // Its tets' boxes, though most of them were never made (the union
        // taken from the vertices, where every vertex is in a tet).
        const BoxUnion want_union = tet_box_union(world, pairs, b);
        CHECK(reached.body_box(b).lo == want_union.lo);
        CHECK(reached.body_box(b).hi == want_union.hi);
        CHECK(full.body_box(b).lo == want_union.lo);
        CHECK(full.body_box(b).hi == want_union.hi);
      }
    });
    {
      std::vector<std::vector<Vec3>> before;
      for (const Body& b : world.bodies) before.push_back(b.x_m);
      TetHashDetector again(world, settings);
      again.hash_tets(world, pairs, nullptr, true);
      move_bodies(world, settings.cell_size_m, 2.5, 0.3);
      INFO("hashed again, moved 2.5 cells");
      TetHashDetector moved_full(world, settings);
      CHECK(again.hash_tets(world, pairs, nullptr, true) == moved_full.hash_tets(world, pairs));
      // (Bodies moved far apart may need too large a grid: then the table
      // hashes, and only whole tets are left out.)
      const ReachableEntries moved = reachable_entries(world, pairs, settings.cell_size_m);
      CHECK(again.hash().entry_count() == (again.hash().dense() ? moved.cells_too : moved.tets_only));
      some_dense_again = some_dense_again || (again.hash().dense() && moved.cells_too < moved.tets_only);
      require_same_queries(world, pairs, moved_full, again);
      for (std::size_t b = 0; b < world.bodies.size(); ++b) world.bodies[b].x_m = before[b];
    }
    TetHashDetector refreshing(world, settings);
    refreshing.enable_refresh();
    CHECK(refreshing.hash_tets(world, pairs, nullptr, true) == full_work);
    CHECK(refreshing.hash().entry_count() == full.hash().entry_count());
    // Every body set to collide with itself (a passive one still does not:
    // self_collision_active).
    for (Body& b : world.bodies) b.self_collision = true;
    INFO("every body with self-collision");
    const CollisionPairs all_self(world);
    TetHashDetector full_self(world, settings), reached_self(world, settings);
    CHECK(reached_self.hash_tets(world, all_self, nullptr, true) == full_self.hash_tets(world, all_self));
    const ReachableEntries want_self = reachable_entries(world, all_self, settings.cell_size_m);
    CHECK(reached_self.hash().entry_count() == want_self.cells_too);
    CHECK(reached_self.cells_told_apart() == want_self.tags_pay);
    require_same_queries(world, all_self, full_self, reached_self);
    // Every walked body colliding with itself: not told apart, and telling
    // them apart would have left some out.
    bool every_walked_self = true;
    for (std::size_t b = 0; b < world.bodies.size(); ++b)
      every_walked_self = every_walked_self && (!all_self.has_partner(b) || all_self.enabled(b, b));
    some_all_self = some_all_self || (every_walked_self && !reached_self.cells_told_apart() &&
                                      want_self.told_apart < want_self.tets_only);
  });
  CHECK(some_skipped);
  CHECK(some_cells_left_out);
  CHECK(some_all_self);
  CHECK(some_dense_again);
  CHECK(some_unmade);
  CHECK(some_told_apart);
  INFO("a scene where telling cells apart would leave entries out, but no body has under a quarter of its "
       "vertices in taking cells");
  CHECK(some_declined);
}

TEST_CASE("a body with vertices in no tet: its union is its tets' boxes', not its vertices', and the table and every "
          "query are as without the shortcut",
          "[detection][threads]") {
  // Where every vertex of a body lies in one of its non-degenerate tets,
  // hash_tets() takes the body's union from its vertices and leaves out a
  // tet no tag takes before making its box. A body with an isolated vertex,
  // and four more only in a degenerate tet, all 1.5 cells beyond its box,
  // must not: its union is still its tets' boxes' alone (a query point
  // between the two is rejected by the union, so a union grown to the
  // vertices would change no answer here; the union itself is checked).
  // The table must hold exactly reachable_entries()'s count (the stray
  // vertices tag their cells like any other), and every query find and be
  // charged what the full table gives, on 0 to 2 threads.
  bool some_body_grown = false;
  for_each_scene_apart([&](World& world, const CollisionPairs& pairs, const DetectionSettings& settings) {
    std::size_t b = 0;
    while (b < world.bodies.size() && !pairs.has_partner(b)) ++b;
    REQUIRE(b < world.bodies.size());
    Body& body = world.bodies[b];
    TetMesh mesh = *body.mesh;
    BoxUnion vertices;
    for (const Vec3& p : body.x_m) vertices.add_box(p, p);
    const Vec3 beyond = vertices.hi + Vec3::Constant(1.5 * settings.cell_size_m);
    const auto add_vertex = [&](const Vec3& p) {
      mesh.positions_m.push_back(p);
      body.x_m.push_back(p);
      return static_cast<std::int32_t>(body.x_m.size() - 1);
    };
    add_vertex(beyond);  // isolated
    const double h = 0.3 * settings.cell_size_m;
    const Tet flat{add_vertex(beyond + Vec3(h, 0, 0)), add_vertex(beyond + Vec3(0, h, 0)),
                   add_vertex(beyond + Vec3(h, h, 0)), add_vertex(beyond + Vec3(2 * h, h, 0))};
    mesh.tets.push_back(flat);  // all four in the plane z = beyond.z
    mesh.is_degenerate.push_back(1);
    body.mesh = std::make_shared<const TetMesh>(std::move(mesh));
    const BoxUnion want_union = tet_box_union(world, pairs, b);
    some_body_grown = some_body_grown || (want_union.hi.array() < beyond.array()).all();
    TetHashDetector full(world, settings);
    const std::uint64_t full_work = full.hash_tets(world, pairs);
    check_reached(world, pairs, settings, full, full_work, [&](const TetHashDetector& reached,
                                                               const ReachableEntries&) {
      for (const TetHashDetector* detector : {static_cast<const TetHashDetector*>(&full), &reached})
        for (std::size_t o = 0; o < world.bodies.size(); ++o) {
          INFO("body " << o);
          const BoxUnion union_o = tet_box_union(world, pairs, o);
          CHECK(detector->body_box(o).lo == union_o.lo);
          CHECK(detector->body_box(o).hi == union_o.hi);
        }
    });
  });
  CHECK(some_body_grown);
}

TEST_CASE("a dense grid in place of the hash answers and charges every query, and the hash, as the hashed table; "
          "a table that may be widened or refreshed keeps the hash",
          "[detection][dense][threads]") {
  // Without enable_widening() or enable_refresh(), hash_tets() lays the
  // table out as a dense grid (where its range is small enough: every test
  // scene's is). Each vertex's query, before and after the bodies moved,
  // must find and be charged what it is with the hashed table (a
  // detector with enable_widening(), whose table hashes), and the hash's
  // work must be the same, with and without the skip of unreachable tets,
  // on 0 to 2 threads. A widened query of a dense table is refused.
  for_each_scene_apart([&](World& world, const CollisionPairs& pairs, const DetectionSettings& settings) {
    std::vector<std::vector<Vec3>> at_hash;  // the positions both tables are hashed at
    for (const Body& b : world.bodies) at_hash.push_back(b.x_m);
    const auto back_to_hash = [&] {
      for (std::size_t b = 0; b < world.bodies.size(); ++b) world.bodies[b].x_m = at_hash[b];
    };
    for (const bool skip : {false, true}) {
      back_to_hash();
      TetHashDetector hashed(world, settings);
      hashed.enable_widening();
      const std::uint64_t hashed_work = hashed.hash_tets(world, pairs, nullptr, skip);
      REQUIRE_FALSE(hashed.hash().dense());
      for (const int threads : {0, 1, 2}) {
        INFO(threads << " threads, skip " << skip);
        WorkerPool pool(std::max(threads, 1));
        back_to_hash();  // the last thread count moved them on
        TetHashDetector dense(world, settings);
        CHECK(dense.hash_tets(world, pairs, threads > 0 ? &pool : nullptr, skip) == hashed_work);
        REQUIRE(dense.hash().dense());
        // Skipping, the grid also leaves out a tet's cells that hold no
        // other body's vertex, which the hash cannot tell apart in a bucket.
        if (skip) {
          const ReachableEntries want = reachable_entries(world, pairs, settings.cell_size_m);
          CHECK(dense.hash().entry_count() == want.cells_too);
          CHECK(hashed.hash().entry_count() == want.tets_only);
        } else {
          CHECK(dense.hash().entry_count() == hashed.hash().entry_count());
        }
        // At the hash's positions, then moved on (a cycle spanning steps
        // queries its table later: unless skipping, which promises not).
        require_same_queries(world, pairs, hashed, dense);
        if (!skip) {
          move_bodies(world, settings.cell_size_m, 0.7, 0.3);
          INFO("moved on 0.7 cells");
          require_same_queries(world, pairs, hashed, dense);
        }
        std::uint64_t work = 0;
        CHECK_THROWS_AS(dense.query_point(world, pairs, 0, 0, work, 0.1 * settings.cell_size_m), std::logic_error);
        CHECK_THROWS_AS(dense.query_point(world, pairs, 0, 0, work, std::numeric_limits<double>::quiet_NaN()),
                        std::logic_error);
      }
    }
    back_to_hash();
    TetHashDetector refreshing(world, settings);
    refreshing.enable_refresh();
    refreshing.hash_tets(world, pairs);
    CHECK_FALSE(refreshing.hash().dense());
  });
}

TEST_CASE("bodies far apart: a dense grid over them would be too large, so the table hashes, and answers and charges "
          "as the hashed table",
          "[detection][dense]") {
  int refused = 0;
  for (const auto& [name, scene] : test::collision_scenes()) {
    INFO(name);
    World world = build_world(scene);
    const CollisionPairs pairs(world);
    const DetectionSettings settings = test::settings_of(world, scene).detection;
    // Movable bodies 5000 cells along a diagonal, alternately each way:
    // between two bodies (or a body and a fixed one) some 10^11 cells.
    move_bodies(world, settings.cell_size_m, 5000.0, 0.1);
    TetHashDetector hashed(world, settings);
    hashed.enable_widening();
    TetHashDetector far(world, settings);
    const std::uint64_t want_hash = hashed.hash_tets(world, pairs);
    CHECK(far.hash_tets(world, pairs) == want_hash);
    if (far.hash().dense()) continue;  // one body alone (a self-colliding scene): its grid is small
    ++refused;
    require_same_queries(world, pairs, hashed, far);
  }
  CHECK(refused > 0);
}

TEST_CASE("the detector's tets along a Morton curve answer and charge every query as in the file's order, on every "
          "hashing path, widened and refreshed",
          "[detection][morton][threads]") {
  // DetectionSettings::curve_order only lays the tets out: buckets then list
  // a body's tets in slot order, not file order, and the query must still
  // give the file order's tet (the smallest index) and charge what a scan in
  // file order, stopping at its first hit, is charged. Both layouts, side
  // by side: the one-task hash on 0 to 2 threads, the piecewise hash, a
  // widened query (several buckets, one best-so-far), and a refresh after a
  // move (the overflow searched too).
  for_each_scene_apart([&](World& world, const CollisionPairs& pairs, const DetectionSettings& settings) {
    DetectionSettings file_order = settings;
    file_order.curve_order = false;
    REQUIRE(settings.curve_order);
    for (const int threads : {0, 1, 2}) {
      INFO(threads << " threads");
      WorkerPool pool(std::max(threads, 1));
      WorkerPool* p = threads > 0 ? &pool : nullptr;
      TetHashDetector want(world, file_order), got(world, settings);
      CHECK(got.hash_tets(world, pairs, p) == want.hash_tets(world, pairs, p));
      require_same_queries(world, pairs, want, got);
    }
    {
      INFO("piecewise, widened a third of a cell");
      TetHashDetector want(world, file_order), got(world, settings);
      want.enable_widening();
      got.enable_widening();
      want.begin_hash();
      got.begin_hash();
      std::uint64_t want_work = 0, got_work = 0;
      for (bool done = false; !done;) want_work += want.hash_some_tets(world, pairs, 7, done);
      for (bool done = false; !done;) got_work += got.hash_some_tets(world, pairs, 7, done);
      want.mutable_hash().build();
      got.mutable_hash().build();
      CHECK(got_work == want_work);
      require_same_queries(world, pairs, want, got);
      require_same_queries(world, pairs, want, got, settings.cell_size_m / 3.0);
    }
    {
      INFO("refreshed after a move, whole and piecewise");
      TetHashDetector want(world, file_order), got(world, settings), got_pieces(world, settings);
      for (TetHashDetector* d : {&want, &got, &got_pieces}) {
        d->enable_refresh();
        d->hash_tets(world, pairs);
      }
      move_bodies(world, settings.cell_size_m, 0.8, 0.3);
      WorkerPool pool(2);
      const std::uint64_t want_work = want.refresh_tets(world, pairs, &pool);
      CHECK(got.refresh_tets(world, pairs, &pool) == want_work);
      CHECK(refresh(world, pairs, got_pieces, 5) == want_work);
      CHECK(got.overflow_tets() == want.overflow_tets());
      require_same_queries(world, pairs, want, got);
      require_same_queries(world, pairs, want, got_pieces);
      require_same_queries(world, pairs, want, got, settings.cell_size_m / 4.0);
    }
  });
}
