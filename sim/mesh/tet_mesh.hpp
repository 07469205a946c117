#pragma once
/// A tetrahedral mesh with the topology the simulation and collision handling
/// need (METHOD.md section 1): unique edges, vertex-vertex adjacency,
/// vertex-tet incidence and the boundary surface.
///
/// Contract of build_tet_mesh():
/// - Orientation: every tet is stored positively oriented, orient3d(v0, v1,
///   v2, v3) > 0, decided by the exact predicate. A tet given with negative
///   orientation is repaired by swapping v2 and v3 and counted in
///   `inverted_tets`. A tet whose four vertices are exactly coplanar (exact
///   orientation 0) is kept as given, counted in `degenerate_tets` and listed
///   in `degenerate_tet_ids`: dynamics give it no mass and no stiffness, and
///   the collision stages skip it, so nothing ever divides by its volume.
/// - Surface: the tet faces that belong to exactly one tet, ordered so their
///   normal (b-a) x (c-a) points out of that tet, found by sorting the 4T face
///   keys (O(T log T)). A face shared by three or more tets makes the mesh
///   non-manifold: build_tet_mesh throws MeshError.
/// - Folds: an interior face whose two tets wind it the same way means both
///   tets lie on the same side of it (the mesh overlaps itself there). Such
///   faces are counted in `folded_faces`, not repaired; the surface is then not
///   closed around the fold (real files have them: dog.mesh has 7).
/// - A tet that repeats a vertex index, or an index out of range, throws.
/// - Vertices used by no tet are kept (indices stay as in the file) and counted
///   in `isolated_vertices`; they have no mass and are never integrated.
/// Units: positions in metres, volumes in cubic metres.

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace tcb {

using Vec3 = Eigen::Vector3d;
using Tet = std::array<std::int32_t, 4>;
using Triangle = std::array<std::int32_t, 3>;
using Edge = std::array<std::int32_t, 2>;

/// A structural problem of a mesh (not tied to a file line).
class MeshError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Compressed adjacency lists: the neighbours of item i are
/// items[offsets[i] .. offsets[i+1]).
struct Adjacency {
  std::vector<std::int32_t> offsets;
  std::vector<std::int32_t> items;
  std::size_t count(std::size_t i) const { return offsets[i + 1] - offsets[i]; }
  const std::int32_t* begin(std::size_t i) const { return items.data() + offsets[i]; }
  const std::int32_t* end(std::size_t i) const { return items.data() + offsets[i + 1]; }
};

struct TetMesh {
  std::vector<Vec3> positions_m;  ///< rest positions
  std::vector<Tet> tets;          ///< positively oriented (see contract)
  /// Per tet, the part it belongs to (a MEDIT element reference, or the box
  /// generator's parts=), or empty: no parts. Parts mean nothing to the
  /// simulation or to the method; the oracle uses them to tell the fold a
  /// vertex entered from the vertex's own neighbourhood (oracle/self_depth.hpp).
  std::vector<std::int32_t> tet_part;
  /// Per vertex, its index in the file it was loaded from, when the vertices
  /// were renumbered at load (sim/mesh/curve_numbering.hpp); empty: the
  /// file's numbering. Every output that names or lists vertices maps
  /// through it (file_vertex() and in_file_order() there), so files stay
  /// in the file's numbering whatever the simulation's.
  std::vector<std::int32_t> file_vertex_id;

  std::vector<Edge> edges;                  ///< unique, each (lo, hi), sorted
  Adjacency vertex_neighbours;              ///< vertex -> vertices sharing an edge
  Adjacency vertex_tets;                    ///< vertex -> incident tets
  std::vector<Triangle> surface;            ///< boundary triangles, outward
  std::vector<std::int32_t> surface_tet;    ///< the tet each surface triangle bounds
  std::vector<std::int32_t> surface_vertices;  ///< sorted unique vertices on the surface

  std::int64_t inverted_tets = 0;     ///< given with negative orientation, repaired
  std::int64_t degenerate_tets = 0;   ///< exactly flat, kept but inert
  std::vector<std::int32_t> degenerate_tet_ids;
  std::vector<char> is_degenerate;    ///< per tet: 1 when exactly flat (the ids above as flags)
  std::int64_t isolated_vertices = 0;
  std::int64_t folded_faces = 0;      ///< interior faces with both tets on one side

  std::size_t vertex_count() const { return positions_m.size(); }
  std::size_t tet_count() const { return tets.size(); }
};

/// Builds a mesh from raw vertices and tets (any orientation); see contract.
TetMesh build_tet_mesh(std::vector<Vec3> positions_m, std::vector<Tet> tets);

/// The four outward faces of a positively oriented tet (v0, v1, v2, v3); face
/// k is opposite vertex k.
std::array<Triangle, 4> tet_faces(const Tet& tet);

/// Signed volume (m^3) of tet (a, b, c, d) in floating point: positive when
/// orient3d(a, b, c, d) > 0 (up to rounding near zero).
double signed_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

/// Sum of the signed tet volumes at the given positions.
double total_volume(const TetMesh& mesh, const std::vector<Vec3>& positions_m);

/// Mean-ratio-like quality 6*sqrt(2)*V / l_rms^3: 1 for a regular tet, 0 for a
/// flat one, negative for an inverted one.
double tet_quality(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

/// The number of distinct parts (TetMesh::tet_part); 1 for a mesh without parts.
std::size_t part_count(const TetMesh& mesh);

/// Euler characteristic V - E + F of the boundary surface (2 for each closed
/// genus-0 component).
std::int64_t surface_euler_characteristic(const TetMesh& mesh);

}  // namespace tcb
