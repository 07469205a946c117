#pragma once
/// A mesh's vertices renumbered along a Morton curve at load, for memory
/// locality (the scene setting `mesh_order = "curve"`): real meshes number
/// their vertices with poor locality (PERFORMANCE.md), so the collision
/// cycle's walks over vertices and the tets' gathers of their corners miss
/// the cache. Renumbered, vertices near each other in space sit near each
/// other in memory.
///
/// Contract of vertices_along_curve():
/// - The vertices are sorted by the Morton key (sim/mesh/morton_key.hpp) of
///   their rest positions within the mesh's box, equal keys in file order (a
///   stable sort): the numbering is a function of the mesh alone.
/// - Each tet keeps its place and its corners in the same order, renamed;
///   parts are kept; the topology is rebuilt by build_tet_mesh(), so edges,
///   adjacency and surface are the same sets under the renaming (their list
///   order follows the new numbers).
/// - file_vertex_id[v] is the file's index of vertex v, composed with any
///   earlier renumbering, so renumbering twice still maps to the file.
/// - A mesh with no vertices is returned as it is.
///
/// This changes results, which is why it is a scene setting (default off)
/// and never the paper's method's default: the order of sums over vertices
/// and surface triangles, and which candidate a smallest-index tie-break
/// picks, follow the numbering, so without a budget a run's figures differ
/// from the file numbering's in rounding and in tie-breaks. Under a budget
/// the difference is larger: a cycle works through points and surface
/// triangles in numbered order, so which points an interrupted cycle
/// reaches first follows the numbering, and with them its forces, the
/// motion, recall and latency (experiments/sweeps/mesh_order.toml measures
/// both orders side by side).
/// What a run writes stays in the file's numbering (tet_mesh.hpp).

#include <cstdint>
#include <vector>

#include "sim/mesh/tet_mesh.hpp"

namespace tcb {

/// The mesh with its vertices renumbered along a Morton curve (contract above).
TetMesh vertices_along_curve(const TetMesh& mesh);

/// The mesh with its vertices renumbered in a given order: vertex v of the
/// result is vertex order[v] of `mesh` (order a permutation of its
/// vertices). Tets, parts, the file's counts and file_vertex_id are carried
/// as vertices_along_curve()'s contract says; it is that function's
/// renaming, for any order.
TetMesh with_vertices_in_order(const TetMesh& mesh, const std::vector<std::uint32_t>& order);

/// The file's index of vertex v (v itself when the mesh was not renumbered).
inline std::int32_t file_vertex(const TetMesh& mesh, std::int32_t v) {
  return mesh.file_vertex_id.empty() ? v : mesh.file_vertex_id[static_cast<std::size_t>(v)];
}

/// Per-vertex values (positions, velocities, masses) in the file's order:
/// scratch[file_vertex(mesh, v)] = values[v], and scratch is returned.
/// Without a renumbering, values itself is returned and nothing is copied
/// (a run in the file's order pays nothing for the variant). values must
/// have one entry per vertex.
template <class T>
const std::vector<T>& in_file_order(const TetMesh& mesh, const std::vector<T>& values, std::vector<T>& scratch) {
  if (mesh.file_vertex_id.empty()) return values;
  scratch.resize(values.size());
  for (std::size_t v = 0; v < values.size(); ++v) scratch[static_cast<std::size_t>(mesh.file_vertex_id[v])] = values[v];
  return scratch;
}

}  // namespace tcb
