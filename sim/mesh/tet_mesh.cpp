#include "sim/mesh/tet_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "sim/geometry/orient3d.hpp"

namespace tcb {
namespace {

Adjacency build_adjacency(std::size_t item_count, const std::vector<std::array<std::int32_t, 2>>& pairs) {
  Adjacency adj;
  adj.offsets.assign(item_count + 1, 0);
  for (const auto& p : pairs) ++adj.offsets[p[0] + 1];
  std::partial_sum(adj.offsets.begin(), adj.offsets.end(), adj.offsets.begin());
  adj.items.resize(pairs.size());
  std::vector<std::int32_t> fill(adj.offsets.begin(), adj.offsets.end() - 1);
  for (const auto& p : pairs) adj.items[fill[p[0]]++] = p[1];
  for (std::size_t i = 0; i < item_count; ++i)
    std::sort(adj.items.begin() + adj.offsets[i], adj.items.begin() + adj.offsets[i + 1]);
  return adj;
}

// Whether two triangles on the same vertices have the same cyclic order.
bool same_winding(const Triangle& a, const Triangle& b) {
  for (int r = 0; r < 3; ++r)
    if (a[0] == b[r] && a[1] == b[(r + 1) % 3] && a[2] == b[(r + 2) % 3]) return true;
  return false;
}

}  // namespace

std::array<Triangle, 4> tet_faces(const Tet& t) {
  // For a positive tet, face k (opposite vertex k) with this winding has its
  // normal pointing away from vertex k.
  return {{{t[1], t[2], t[3]}, {t[0], t[3], t[2]}, {t[0], t[1], t[3]}, {t[0], t[2], t[1]}}};
}

double signed_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return (b - a).dot((c - a).cross(d - a)) / 6.0;
}

double tet_quality(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const double sum_sq = (b - a).squaredNorm() + (c - a).squaredNorm() + (d - a).squaredNorm() +
                        (c - b).squaredNorm() + (d - b).squaredNorm() + (d - c).squaredNorm();
  if (sum_sq == 0.0) return 0.0;
  const double l_rms = std::sqrt(sum_sq / 6.0);
  return 6.0 * std::sqrt(2.0) * signed_volume(a, b, c, d) / (l_rms * l_rms * l_rms);
}

double total_volume(const TetMesh& mesh, const std::vector<Vec3>& x) {
  double v = 0.0;
  for (const Tet& t : mesh.tets) v += signed_volume(x[t[0]], x[t[1]], x[t[2]], x[t[3]]);
  return v;
}

TetMesh build_tet_mesh(std::vector<Vec3> positions_m, std::vector<Tet> tets) {
  TetMesh mesh;
  mesh.positions_m = std::move(positions_m);
  mesh.tets = std::move(tets);
  const auto n = static_cast<std::int64_t>(mesh.positions_m.size());

  std::vector<char> used(mesh.positions_m.size(), 0);
  mesh.is_degenerate.assign(mesh.tets.size(), 0);
  for (std::size_t i = 0; i < mesh.tets.size(); ++i) {
    Tet& t = mesh.tets[i];
    for (int k = 0; k < 4; ++k) {
      if (t[k] < 0 || t[k] >= n)
        throw MeshError("tet " + std::to_string(i) + " has vertex index " + std::to_string(t[k]) +
                        " outside [0, " + std::to_string(n) + ")");
      for (int j = 0; j < k; ++j)
        if (t[j] == t[k])
          throw MeshError("tet " + std::to_string(i) + " repeats vertex " + std::to_string(t[k]));
      used[t[k]] = 1;
    }
    const auto& x = mesh.positions_m;
    const int o = orient3d(x[t[0]], x[t[1]], x[t[2]], x[t[3]]);
    if (o < 0) {
      std::swap(t[2], t[3]);
      ++mesh.inverted_tets;
    } else if (o == 0) {
      ++mesh.degenerate_tets;
      mesh.degenerate_tet_ids.push_back(static_cast<std::int32_t>(i));
      mesh.is_degenerate[i] = 1;
    }
  }
  mesh.isolated_vertices = std::count(used.begin(), used.end(), 0);

  // Edges: the 6 per tet, sorted and made unique.
  std::vector<Edge> all_edges;
  all_edges.reserve(mesh.tets.size() * 6);
  for (const Tet& t : mesh.tets)
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) all_edges.push_back({std::min(t[a], t[b]), std::max(t[a], t[b])});
  std::sort(all_edges.begin(), all_edges.end());
  all_edges.erase(std::unique(all_edges.begin(), all_edges.end()), all_edges.end());
  mesh.edges = std::move(all_edges);

  std::vector<std::array<std::int32_t, 2>> pairs;
  pairs.reserve(mesh.edges.size() * 2);
  for (const Edge& e : mesh.edges) {
    pairs.push_back({e[0], e[1]});
    pairs.push_back({e[1], e[0]});
  }
  mesh.vertex_neighbours = build_adjacency(mesh.positions_m.size(), pairs);
  pairs.clear();
  for (std::size_t i = 0; i < mesh.tets.size(); ++i)
    for (int k = 0; k < 4; ++k) pairs.push_back({mesh.tets[i][k], static_cast<std::int32_t>(i)});
  mesh.vertex_tets = build_adjacency(mesh.positions_m.size(), pairs);

  // Boundary: sort the 4T faces by their sorted vertex triple; a key that
  // occurs once is a boundary face.
  struct FaceRecord {
    Triangle key;
    Triangle face;
    std::int32_t tet;
  };
  std::vector<FaceRecord> faces;
  faces.reserve(mesh.tets.size() * 4);
  for (std::size_t i = 0; i < mesh.tets.size(); ++i) {
    for (const Triangle& f : tet_faces(mesh.tets[i])) {
      Triangle key = f;
      std::sort(key.begin(), key.end());
      faces.push_back({key, f, static_cast<std::int32_t>(i)});
    }
  }
  std::sort(faces.begin(), faces.end(),
            [](const FaceRecord& a, const FaceRecord& b) { return a.key < b.key; });
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i + 1;
    while (j < faces.size() && faces[j].key == faces[i].key) ++j;
    if (j - i == 1) {
      mesh.surface.push_back(faces[i].face);
      mesh.surface_tet.push_back(faces[i].tet);
    } else if (j - i == 2) {
      if (same_winding(faces[i].face, faces[i + 1].face)) ++mesh.folded_faces;
    } else if (j - i > 2) {
      const Triangle& k = faces[i].key;
      throw MeshError("non-manifold mesh: face (" + std::to_string(k[0]) + ", " +
                      std::to_string(k[1]) + ", " + std::to_string(k[2]) + ") is shared by " +
                      std::to_string(j - i) + " tets");
    }
    i = j;
  }
  for (const Triangle& f : mesh.surface) mesh.surface_vertices.insert(mesh.surface_vertices.end(), f.begin(), f.end());
  std::sort(mesh.surface_vertices.begin(), mesh.surface_vertices.end());
  mesh.surface_vertices.erase(std::unique(mesh.surface_vertices.begin(), mesh.surface_vertices.end()),
                              mesh.surface_vertices.end());
  return mesh;
}

std::int64_t surface_euler_characteristic(const TetMesh& mesh) {
  std::vector<Edge> edges;
  edges.reserve(mesh.surface.size() * 3);
  for (const Triangle& f : mesh.surface)
    for (int k = 0; k < 3; ++k) {
      const auto a = f[k], b = f[(k + 1) % 3];
      edges.push_back({std::min(a, b), std::max(a, b)});
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return static_cast<std::int64_t>(mesh.surface_vertices.size()) -
         static_cast<std::int64_t>(edges.size()) + static_cast<std::int64_t>(mesh.surface.size());
}

std::size_t part_count(const TetMesh& mesh) {
  std::vector<std::int32_t> parts = mesh.tet_part;
  std::sort(parts.begin(), parts.end());
  return std::max<std::size_t>(static_cast<std::size_t>(std::unique(parts.begin(), parts.end()) - parts.begin()), 1);
}

}  // namespace tcb
