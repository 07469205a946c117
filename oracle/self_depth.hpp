#pragma once
/// The true depth of self-collision points, drawn by the body's parts
/// (TetMesh::tet_part: MEDIT element references, or a generated box's
/// parts=). Independent of method/ (CGAL only).
///
/// Why parts: a vertex p inside its own body's tets (the oracle's
/// self-collision rule, tet_inside.hpp) lies on that body's surface, so its
/// distance to "the surface" is 0; a depth must leave out p's own
/// neighbourhood, and where that ends is a statement about the object, not a
/// constant of the oracle. The scene states it with parts:
/// - p's neighbourhood N(p): the parts of the tets incident to p, and every
///   part that shares a vertex with one of them (mesh topology, rest state);
/// - p is *deep* when it is inside the tets of parts outside N(p) (the same
///   exact three-valued rule as classify_self_points, tet_inside.hpp, with only
///   those tets): those parts are the fold p entered;
/// - a deep point's true depth is its distance to the nearest boundary
///   triangle of the body that bounds a tet of a part outside N(p) (AABB tree
///   over those triangles, Epick: inexact constructions, error ~1e-16
///   relative), as a point inside another body is as deep as its distance to
///   that body's surface. Cut faces between parts are not surface and never
///   count;
/// - every other self-collision point has no true depth: NaN. That is a point
///   inside tets of its own or a neighbouring part only; one that only
///   touches far tets on the body's surface; one whose far parts have no
///   boundary triangle; and every vertex of a body with fewer than two parts.
/// - Ties on a cut face: a point exactly on a face shared by a far tet and a
///   tet of its neighbourhood counts as inside the far part (that face is not
///   surface) and gets its distance to the far parts' surface, not 0.
/// tet_part must be empty or have one entry per tet (std::invalid_argument).
/// When each part is a connected component of its own, a self-collision depth
/// is exactly the oracle's depth for the components as separate bodies
/// (tested). Units: metres.

#include <vector>

#include "oracle/tet_inside.hpp"
#include "sim/world/world.hpp"

namespace tcb {

struct SelfDepths {
  std::vector<double> depth_m;  ///< per vertex: true depth of a deep point, else NaN
  std::int64_t deep = 0;        ///< self-collision points with a depth
  std::int64_t shallow = 0;     ///< self-collision points inside their neighbourhood only (NaN)
};

/// `self_sides`: classify_self_points(body). Only its Inside vertices get a
/// depth (or NaN); every other vertex is NaN and counted in neither.
SelfDepths self_collision_depths(const Body& body, const std::vector<TetSide>& self_sides);

}  // namespace tcb
