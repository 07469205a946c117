// Vertices renumbered along a Morton curve at load: the same mesh under a
// renaming (positions, tets, parts, surface), a numbering that is local
// where the file's is not, and a map back to the file that composes.
#include "sim/mesh/curve_numbering.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>
#include <numeric>
#include <random>
#include <set>
#include <string>

#include "sim/mesh/box_mesh.hpp"
#include "sim/mesh/medit_io.hpp"
#include "sim/mesh/morton_key.hpp"

using namespace tcb;

namespace {

// The mesh with its vertices shuffled (a file with no locality), parts kept;
// with keep_map, file_vertex_id maps the result back to the given mesh's
// file, as a renumbering at load would.
TetMesh shuffled(const TetMesh& mesh, unsigned seed, bool keep_map = false) {
  std::vector<std::uint32_t> order(static_cast<std::size_t>(mesh.vertex_count()));
  std::iota(order.begin(), order.end(), 0u);
  std::shuffle(order.begin(), order.end(), std::mt19937(seed));
  TetMesh out = with_vertices_in_order(mesh, order);
  if (!keep_map) out.file_vertex_id.clear();  // a file of its own
  return out;
}

// The median |i - j| over the mesh's edges: how far apart in memory
// neighbours sit (a Morton curve jumps between octants, so a few edges
// stay long; the median is what most gathers see).
double median_edge_span(const TetMesh& mesh) {
  std::vector<std::int32_t> span;
  for (const Edge& e : mesh.edges) span.push_back(std::abs(e[1] - e[0]));
  std::nth_element(span.begin(), span.begin() + static_cast<std::ptrdiff_t>(span.size() / 2), span.end());
  return span[span.size() / 2];
}

// The renumbered mesh is the given one under file_vertex_id: same positions,
// the same tets in the same places with their corners in the same order,
// parts, surface and edges the same sets once renamed back.
void check_same_mesh(const TetMesh& given, const TetMesh& renumbered) {
  REQUIRE(renumbered.vertex_count() == given.vertex_count());
  REQUIRE(renumbered.file_vertex_id.size() == given.vertex_count());
  std::vector<std::int32_t> ids = renumbered.file_vertex_id;
  std::sort(ids.begin(), ids.end());
  for (std::size_t i = 0; i < ids.size(); ++i) REQUIRE(ids[i] == static_cast<std::int32_t>(i));  // a permutation
  const auto back = [&](std::int32_t v) { return file_vertex(renumbered, v); };
  for (std::size_t v = 0; v < renumbered.vertex_count(); ++v)
    CHECK(renumbered.positions_m[v] == given.positions_m[static_cast<std::size_t>(back(static_cast<std::int32_t>(v)))]);
  std::vector<Vec3> scratch;
  CHECK(in_file_order(renumbered, renumbered.positions_m, scratch) == given.positions_m);
  REQUIRE(renumbered.tet_count() == given.tet_count());
  for (std::size_t t = 0; t < given.tet_count(); ++t)
    for (int k = 0; k < 4; ++k) CHECK(back(renumbered.tets[t][k]) == given.tets[t][k]);
  CHECK(renumbered.tet_part == given.tet_part);
  const auto rotated = [](Triangle t) {  // a triangle by its smallest corner first, winding kept
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    return t;
  };
  std::set<Triangle> surface, surface_back;
  for (const Triangle& t : given.surface) surface.insert(rotated(t));
  for (const Triangle& t : renumbered.surface) surface_back.insert(rotated({back(t[0]), back(t[1]), back(t[2])}));
  CHECK(surface_back == surface);
  std::set<Edge> edges, edges_back;
  for (const Edge& e : given.edges) edges.insert(e);
  for (const Edge& e : renumbered.edges)
    edges_back.insert({std::min(back(e[0]), back(e[1])), std::max(back(e[0]), back(e[1]))});
  CHECK(edges_back == edges);
  CHECK(renumbered.inverted_tets == given.inverted_tets);
  CHECK(renumbered.degenerate_tets == given.degenerate_tets);
  CHECK(renumbered.folded_faces == given.folded_faces);
}

}  // namespace

TEST_CASE("vertices along the curve: the same mesh renamed, sorted by Morton key, and local where the file is not",
          "[mesh][curve]") {
  const TetMesh box = make_box_mesh(Vec3(0.3, 0.1, 0.2), 15, 15, 15, {3, 1, 2});
  const TetMesh given = shuffled(box, 7);
  const TetMesh renumbered = vertices_along_curve(given);
  check_same_mesh(given, renumbered);
  const auto [lo, hi] = bounding_box(given.positions_m);
  for (std::size_t v = 1; v < renumbered.vertex_count(); ++v) {
    const std::uint64_t a = morton_key(renumbered.positions_m[v - 1], lo, hi);
    const std::uint64_t b = morton_key(renumbered.positions_m[v], lo, hi);
    REQUIRE(a <= b);
    // Equal keys keep the file's order (the box's vertices all differ, so
    // this only guards the stable sort where keys tie).
    if (a == b) CHECK(renumbered.file_vertex_id[v - 1] < renumbered.file_vertex_id[v]);
  }
  // Shuffled, an edge's two ends sit about a third of the mesh apart; along
  // the curve, most of them a few places apart.
  CHECK(median_edge_span(renumbered) < 0.05 * median_edge_span(given));
}

TEST_CASE("vertices along the curve: a real mesh keeps its folds and counts, and renumbering twice still maps to "
          "the file",
          "[mesh][curve]") {
  const TetMesh dog = read_medit(std::string(TCBENCH_SHARED_MESHES) + "/dog.mesh");
  const TetMesh once = vertices_along_curve(dog);
  check_same_mesh(dog, once);
  CHECK(median_edge_span(once) < 0.05 * median_edge_span(dog));  // 723 in the file, 13 along the curve
  // Sorted already: a second pass keeps every vertex in place, and its map
  // is still the file's.
  const TetMesh twice = vertices_along_curve(once);
  CHECK(twice.file_vertex_id == once.file_vertex_id);
  CHECK(twice.positions_m == once.positions_m);
  check_same_mesh(dog, twice);
}

TEST_CASE("vertices along the curve: a mesh renumbered before is renumbered again and still maps to its file",
          "[mesh][curve]") {
  // The input carries a map of its own (a shuffle away from the box's
  // file), so this pass moves vertices and must compose the two maps: a map
  // to its input's numbering instead would fail check_same_mesh.
  const TetMesh box = make_box_mesh(Vec3(0.2, 0.1, 0.3), 6, 3, 7, {2, 1, 1});
  const TetMesh moved = shuffled(box, 11, true);
  const TetMesh renumbered = vertices_along_curve(moved);
  REQUIRE(renumbered.positions_m != moved.positions_m);
  check_same_mesh(box, renumbered);
}

TEST_CASE("vertices along the curve: coincident vertices keep the file's order, and an inverted tet stays counted",
          "[mesh][curve]") {
  // Vertex 5 repeats vertex 2's position (equal keys) and no tet uses it;
  // the second tet is given with negative orientation (build_tet_mesh
  // repairs it and counts it).
  const std::vector<Vec3> x = {{1.0, 1.0, 1.0}, {0.0, 0.0, 0.0}, {0.5, 0.0, 0.0},
                               {0.0, 0.5, 0.0}, {0.0, 0.0, 0.5}, {0.5, 0.0, 0.0}};
  const TetMesh given = build_tet_mesh(x, {{1, 2, 3, 4}, {0, 2, 3, 4}});
  REQUIRE(given.inverted_tets == 1);
  REQUIRE(given.isolated_vertices == 1);
  const TetMesh renumbered = vertices_along_curve(given);
  check_same_mesh(given, renumbered);
  CHECK(renumbered.isolated_vertices == 1);
  const auto at = [&](std::int32_t file_id) {
    return std::find(renumbered.file_vertex_id.begin(), renumbered.file_vertex_id.end(), file_id) -
           renumbered.file_vertex_id.begin();
  };
  CHECK(at(2) + 1 == at(5));  // equal keys: next to each other, in file order
}

TEST_CASE("without a renumbering, every vertex is its file's, and an empty mesh stays empty", "[mesh][curve]") {
  const TetMesh box = make_box_mesh(Vec3(1.0, 1.0, 1.0), 2, 2, 2);
  CHECK(box.file_vertex_id.empty());
  for (std::int32_t v = 0; v < static_cast<std::int32_t>(box.vertex_count()); ++v) CHECK(file_vertex(box, v) == v);
  std::vector<Vec3> scratch;
  CHECK(&in_file_order(box, box.positions_m, scratch) == &box.positions_m);  // no copy
  CHECK(scratch.empty());
  const TetMesh empty;
  const TetMesh same = vertices_along_curve(empty);
  CHECK(same.vertex_count() == 0);
  CHECK(same.file_vertex_id.empty());
}
