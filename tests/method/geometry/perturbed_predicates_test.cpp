// The symbolic tie-break, checked by its consequences on whole conforming
// meshes: every point is inside exactly one tet of a tiling that its perturbed
// position lies in, and every segment crosses a closed surface an odd number
// of times exactly when one end is inside. The query points sit on a lattice
// that hits vertices, edges and faces (including the Kuhn diagonals) exactly.
#include "method/geometry/perturbed_predicates.hpp"

#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <random>

#include "sim/geometry/orient3d.hpp"
#include "sim/mesh/box_mesh.hpp"

using namespace tcb;

namespace {

struct Transform {
  const char* name;
  Eigen::Matrix3d linear = Eigen::Matrix3d::Identity();
  Vec3 shift = Vec3::Zero();
  bool exact = true;  // coordinates transform without rounding
  Vec3 apply(const Vec3& p) const { return linear * p + shift; }
};

std::vector<Transform> transforms() {
  std::vector<Transform> t;
  t.push_back({"identity"});
  Transform perm{"axis permutation and flips"};
  perm.linear << 0, -1, 0, 0, 0, 1, -1, 0, 0;
  t.push_back(perm);
  Transform pow2{"scale 2^-10, shift"};
  pow2.linear *= std::ldexp(1.0, -10);
  pow2.shift = Vec3(3.0, -5.0, 0.5);
  t.push_back(pow2);
  std::mt19937 rng(99);
  std::normal_distribution<double> n;
  for (double scale : {1e-3, 1.0, 1e3}) {
    Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
    q.normalize();
    Transform r{"random rotation and scale"};
    r.linear = scale * q.toRotationMatrix();
    r.shift = scale * Vec3(n(rng), n(rng), n(rng));
    r.exact = false;
    t.push_back(r);
  }
  return t;
}

int tets_containing(const Vec3& p, const std::vector<Vec3>& x, const TetMesh& mesh) {
  int count = 0;
  for (const Tet& t : mesh.tets) count += point_in_tet_perturbed(p, x[t[0]], x[t[1]], x[t[2]], x[t[3]]);
  return count;
}

int surface_crossings(const Vec3& p, const Vec3& q, const std::vector<Vec3>& x, const TetMesh& mesh) {
  int count = 0;
  for (const Triangle& f : mesh.surface) count += segment_crosses_triangle_perturbed(p, q, x[f[0]], x[f[1]], x[f[2]]);
  return count;
}

// Where p + delta lies for the untransformed box [-1, 1]^3 under an exact
// transform: inside iff each coordinate is in [lo, hi) after the transform
// (delta is positive on every axis).
bool inside_transformed_box(const Vec3& p_world, const Transform& t) {
  const Vec3 a = t.apply(Vec3(-1, -1, -1)), b = t.apply(Vec3(1, 1, 1));
  for (int k = 0; k < 3; ++k) {
    const double lo = std::min(a[k], b[k]), hi = std::max(a[k], b[k]);
    if (!(p_world[k] >= lo && p_world[k] < hi)) return false;
  }
  return true;
}

// point_in_tet_perturbed() by the definition alone, every sign by the
// exact expansion path (no filter, no shortcut): the reference for the
// randomized comparison below.
int reference_point_side(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p) {
  if (const int s = orient3d_exact(a, b, c, p); s != 0) return s;
  for (int axis = 0; axis < 3; ++axis)
    if (const int s = cross_product_sign_exact(a, b, a, c, axis); s != 0) return s;
  return 0;
}

int reference_edge_side(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b) {
  if (const int s = orient3d_exact(p, q, a, b); s != 0) return s;
  for (int axis = 0; axis < 3; ++axis)
    if (const int s = cross_product_sign_exact(p, q, a, b, axis); s != 0) return s;
  return 0;
}

// segment_crosses_triangle_perturbed() by the definition alone, as above.
bool reference_segment_crosses(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
  const int sp = reference_point_side(a, b, c, p), sq = reference_point_side(a, b, c, q);
  if (sp == 0 || sq == 0 || sp == sq) return false;
  const int s[3] = {reference_edge_side(p, q, a, b), reference_edge_side(p, q, b, c), reference_edge_side(p, q, c, a)};
  return s[0] != 0 && s[0] == s[1] && s[1] == s[2];
}

bool reference_point_in_tet(const Vec3& p, const Vec3& v0, const Vec3& v1, const Vec3& v2, const Vec3& v3) {
  const int s[4] = {reference_point_side(v1, v2, v3, p), reference_point_side(v0, v3, v2, p),
                    reference_point_side(v0, v1, v3, p), reference_point_side(v0, v2, v1, p)};
  return s[0] != 0 && s[0] == s[1] && s[1] == s[2] && s[2] == s[3];
}

}  // namespace

TEST_CASE("perturbed point in tet: named cases on one tet", "[predicates]") {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0), d(0, 0, 1);
  CHECK(point_in_tet_perturbed(Vec3(0.1, 0.1, 0.1), a, b, c, d));
  CHECK_FALSE(point_in_tet_perturbed(Vec3(1, 1, 1), a, b, c, d));
  // On the vertex at the origin: delta points into the tet (all components > 0).
  CHECK(point_in_tet_perturbed(a, a, b, c, d));
  // On face x = 0, y = 0, z = 0: delta has positive components, pointing in.
  CHECK(point_in_tet_perturbed(Vec3(0, 0.25, 0.25), a, b, c, d));
  CHECK(point_in_tet_perturbed(Vec3(0.25, 0.25, 0), a, b, c, d));
  // On the slanted face x + y + z = 1: delta points out.
  CHECK_FALSE(point_in_tet_perturbed(Vec3(0.25, 0.25, 0.5), a, b, c, d));
  // A flat tet contains nothing, not even its own vertices.
  CHECK_FALSE(point_in_tet_perturbed(Vec3(0.2, 0.2, 0), a, b, c, Vec3(0.5, 0.5, 0)));
}

TEST_CASE("perturbed point in tet: an inverted tet contains the region it bounds, as the oracle counts it", "[predicates]") {
  // The same tet with two vertices swapped (negative orientation), as an
  // element inverted by the motion is: the same points are inside, the same
  // touching points decided the same way (the faces are the same planes).
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0), d(0, 0, 1);
  for (const Vec3& p : {Vec3(0.1, 0.1, 0.1), Vec3(1, 1, 1), a, Vec3(0, 0.25, 0.25), Vec3(0.25, 0.25, 0),
                        Vec3(0.25, 0.25, 0.5), Vec3(-0.1, 0.2, 0.2), Vec3(0.3, 0.3, 0.3)}) {
    INFO(p.transpose());
    CHECK(point_in_tet_perturbed(p, a, c, b, d) == point_in_tet_perturbed(p, a, b, c, d));
    CHECK(point_in_tet_perturbed(p, b, a, c, d) == point_in_tet_perturbed(p, a, b, c, d));
  }
  CHECK(point_in_tet_perturbed(Vec3(0.1, 0.1, 0.1), a, c, b, d));
  // A flat tet contains nothing in either vertex order.
  CHECK_FALSE(point_in_tet_perturbed(Vec3(0.2, 0.2, 0), a, c, b, Vec3(0.5, 0.5, 0)));
  CHECK_FALSE(point_in_tet_perturbed(Vec3(0.2, 0.2, 1e-9), a, c, b, Vec3(0.5, 0.5, 0)));
}

TEST_CASE("perturbed point in tet: every lattice point in exactly one tet of a tiling", "[predicates]") {
  const TetMesh mesh = make_box_mesh(Vec3(2, 2, 2), 2, 2, 2);  // vertices at -1, 0, 1
  for (const Transform& t : transforms()) {
    INFO(t.name);
    std::vector<Vec3> x;
    for (const Vec3& p : mesh.positions_m) x.push_back(t.apply(p));
    int on_boundary_cases = 0;
    for (int i = -5; i <= 5; ++i)
      for (int j = -5; j <= 5; ++j)
        for (int k = -5; k <= 5; ++k) {
          const Vec3 p0(i * 0.25, j * 0.25, k * 0.25);  // spacing 1/4: vertices, edges, faces, diagonals
          const Vec3 p = t.apply(p0);
          const int count = tets_containing(p, x, mesh);
          REQUIRE(count <= 1);
          if (t.exact) {
            REQUIRE(count == (inside_transformed_box(p, t) ? 1 : 0));
          } else if (p0.cwiseAbs().maxCoeff() <= 0.75) {
            REQUIRE(count == 1);  // well inside: rounding cannot move it out
          }
          on_boundary_cases += p0.cwiseAbs().maxCoeff() == 1.0;
        }
    CHECK(on_boundary_cases > 0);
  }
}

TEST_CASE("perturbed segment-triangle: crossings of a closed surface have the right parity", "[predicates]") {
  // Segments between lattice points pass exactly through surface vertices,
  // along surface edges and inside the planes of faces.
  const TetMesh mesh = make_box_mesh(Vec3(2, 2, 2), 2, 2, 2);
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> lattice(-6, 6);
  for (const Transform& t : transforms()) {
    INFO(t.name);
    std::vector<Vec3> x;
    for (const Vec3& p : mesh.positions_m) x.push_back(t.apply(p));
    int along_faces = 0;
    for (int trial = 0; trial < 3000; ++trial) {
      Vec3 p0(lattice(rng) * 0.25, lattice(rng) * 0.25, lattice(rng) * 0.25);
      Vec3 q0(lattice(rng) * 0.25, lattice(rng) * 0.25, lattice(rng) * 0.25);
      if (trial % 3 == 0) q0.y() = p0.y() = (trial % 2 ? 1.0 : -1.0);  // in the plane of a face
      if (p0 == q0) continue;
      along_faces += trial % 3 == 0;
      const Vec3 p = t.apply(p0), q = t.apply(q0);
      const bool p_in = tets_containing(p, x, mesh) == 1, q_in = tets_containing(q, x, mesh) == 1;
      const int crossings = surface_crossings(p, q, x, mesh);
      REQUIRE(crossings % 2 == (p_in != q_in ? 1 : 0));
      // An exactly transformed box stays convex: at most two crossings. After a
      // rounded rotation its faces are no longer exactly planar, and a segment
      // in a face plane may weave through them; only the parity is certain.
      if (t.exact) REQUIRE(crossings <= 2);
    }
    CHECK(along_faces > 100);
  }
}

TEST_CASE("a triangle whose box lies apart from a segment's is never crossed by it", "[predicates]") {
  // Lattice points (ends on the triangle's plane, edges and vertices, boxes
  // touching exactly) and general positions, under every transform: each
  // rejection must be a pair the predicate does not cross, and the test
  // needs both rejections and crossings among pairs whose boxes touch or
  // overlap, so that it can fail.
  std::mt19937 rng(23);
  std::uniform_int_distribution<int> lattice(-2, 2);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int apart = 0, crossed = 0, touching_crossed = 0;
  for (const Transform& t : transforms())
    for (int trial = 0; trial < 100000; ++trial) {
      Vec3 v[5];
      for (Vec3& x : v)
        x = trial % 2 ? Vec3(lattice(rng) * 0.5, lattice(rng) * 0.5, lattice(rng) * 0.5) : Vec3(u(rng), u(rng), u(rng));
      for (Vec3& x : v) x = t.apply(x);
      const Vec3 &p = v[0], &q = v[1];
      const Vec3 lo = p.cwiseMin(q), hi = p.cwiseMax(q);
      const bool rejected = triangle_box_apart(lo, hi, v[2], v[3], v[4]);
      const bool crosses = segment_crosses_triangle_perturbed(p, q, v[2], v[3], v[4]);
      INFO(t.name << ", trial " << trial);
      REQUIRE_FALSE((rejected && crosses));
      apart += rejected;
      crossed += crosses;
      // Crossings where the boxes touch along an axis: the edge of the rule.
      const Vec3 tri_lo = v[2].cwiseMin(v[3]).cwiseMin(v[4]), tri_hi = v[2].cwiseMax(v[3]).cwiseMax(v[4]);
      touching_crossed += crosses && ((tri_hi.array() == lo.array()).any() || (tri_lo.array() == hi.array()).any());
    }
  CHECK(apart > 10000);
  CHECK(crossed > 10000);
  CHECK(touching_crossed > 0);
}

TEST_CASE("coplanar stacked plates: the shared face belongs to one side only", "[predicates]") {
  // Plate B sits exactly on plate A. delta points up (+eps^2 in y), so A's
  // top vertices count as inside B where they are not on B's far x/z faces,
  // and B's bottom vertices are never inside A.
  const TetMesh plate = make_box_mesh(Vec3(1, 0.25, 1), 2, 1, 2);  // y in [-0.125, 0.125]
  std::vector<Vec3> a = plate.positions_m, b = plate.positions_m;
  for (Vec3& p : b) p.y() += 0.25;
  int a_in_b = 0, b_in_a = 0;
  for (const Vec3& p : a)
    if (p.y() == 0.125) a_in_b += tets_containing(p, b, plate);
  for (const Vec3& p : b)
    if (p.y() == 0.125) b_in_a += tets_containing(p, a, plate);
  CHECK(a_in_b == 4);  // the 3x3 top grid less the x = 0.5 and z = 0.5 rows
  CHECK(b_in_a == 0);
}

TEST_CASE("segment-plane parameter", "[predicates]") {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  CHECK(segment_plane_parameter(Vec3(0.2, 0.2, 1), Vec3(0.2, 0.2, -3), a, b, c) == Approx(0.25));
  CHECK(segment_plane_parameter(Vec3(0.2, 0.2, 0), Vec3(0.2, 0.2, -3), a, b, c) == 0.0);
}

TEST_CASE("perturbed point in tet: the inline filter answers as the exact path on a million near-degenerate cases",
          "[predicates]") {
  // point_in_tet_perturbed() takes the point's differences once and lets
  // orient3d's filter decide the faces it can without a call (issue 14's
  // floating-point pre-test). Its answer must be the exact one: compared
  // with the four faces' signs from the expansion path alone on 10^6 tets
  // and points where the filter is most likely wrong. Integer tets at scales
  // 2^-60 .. 2^60 with the point at a vertex, on an edge's midpoint, on a
  // face's plane (s a + t b + u c over 4 with s + t + u = 4, exact: inside
  // the face when none is negative; nudged by one unit or not), or the tet
  // nearly flat (its fourth vertex so placed); and double tets with the
  // point computed on a face's plane in floating point and moved 0 .. 2
  // ulps a coordinate. (At a vertex or an edge's midpoint the filter cannot
  // decide the faces through the point, whose computed determinant is
  // exactly 0: those cases try the exact path; the others try the bound.)
  std::mt19937_64 rng(20261128);
  std::uniform_int_distribution<std::int64_t> coord(-(std::int64_t(1) << 30), std::int64_t(1) << 30);
  std::uniform_int_distribution<std::int64_t> small(-2, 2), quarter(-2, 4);
  std::uniform_int_distribution<int> kind(0, 5), vertex(0, 3), nudge(-1, 1), ulps(-2, 2), exponent(-60, 60);
  std::uniform_real_distribution<double> u(-1.0, 1.0), w(-0.5, 1.5);
  constexpr int kCases = 1000000;
  int disagree = 0, inside = 0, open_faces = 0;
  for (int i = 0; i < kCases; ++i) {
    std::array<Vec3, 4> v;
    Vec3 p;
    const int k = kind(rng);
    if (k < 5) {
      std::array<std::array<std::int64_t, 3>, 5> q{};  // four vertices and the point, integers
      for (int r = 0; r < 4; ++r)
        for (int a = 0; a < 3; ++a) q[r][a] = coord(rng);
      const int f0 = vertex(rng), f1 = (f0 + 1) % 4, f2 = (f0 + 2) % 4;
      const std::int64_t s = small(rng), t = small(rng);
      const std::int64_t s4 = quarter(rng), t4 = quarter(rng), u4 = 4 - s4 - t4;
      const int n = k == 3 ? 0 : nudge(rng);
      if (k == 2 || k == 3)  // coordinates divisible by 4: the combination over 4 is exact
        for (int r : {f0, f1, f2})
          for (int a = 0; a < 3; ++a) q[r][a] &= ~std::int64_t(3);
      for (int a = 0; a < 3; ++a) {
        const std::int64_t on_plane = q[f0][a] + s * (q[f1][a] - q[f0][a]) + t * (q[f2][a] - q[f0][a]);
        switch (k) {
          case 0: q[4][a] = q[f0][a]; break;                   // a vertex
          case 1: q[4][a] = (q[f0][a] + q[f1][a]) / 2; break;  // near an edge's middle
          case 2: case 3:                                      // a face's plane
            q[4][a] = (s4 * q[f0][a] + t4 * q[f1][a] + u4 * q[f2][a]) / 4 + n;
            break;
          default:  // a nearly flat tet
            q[(f0 + 3) % 4][a] = on_plane + n;
            q[4][a] = q[f1][a] + s;
            break;
        }
      }
      if (k == 1)  // even coordinates: the midpoint is exact
        for (int a = 0; a < 3; ++a) q[f0][a] &= ~std::int64_t(1), q[f1][a] &= ~std::int64_t(1), q[4][a] = (q[f0][a] + q[f1][a]) / 2;
      const double f = std::ldexp(1.0, exponent(rng));
      for (int r = 0; r < 4; ++r) v[r] = Vec3(q[r][0] * f, q[r][1] * f, q[r][2] * f);
      p = Vec3(q[4][0] * f, q[4][1] * f, q[4][2] * f);
    } else {
      const double f = std::ldexp(1.0, exponent(rng) / 2);
      for (Vec3& x : v) x = Vec3(u(rng), u(rng), u(rng)) * f;
      const int f0 = vertex(rng), f1 = (f0 + 1) % 4, f2 = (f0 + 2) % 4;
      p = v[f0] + w(rng) * (v[f1] - v[f0]) + w(rng) * (v[f2] - v[f0]);
      for (int a = 0; a < 3; ++a)
        for (int n = ulps(rng); n != 0; n += n > 0 ? -1 : 1) p[a] = std::nextafter(p[a], n > 0 ? HUGE_VAL : -HUGE_VAL);
    }
    const bool answer = point_in_tet_perturbed(p, v[0], v[1], v[2], v[3]);
    disagree += answer != reference_point_in_tet(p, v[0], v[1], v[2], v[3]);
    // The public one-face sign, which the test above no longer calls.
    disagree += orient3d_perturbed_point(v[1], v[2], v[3], p) != reference_point_side(v[1], v[2], v[3], p);
    inside += answer;
    open_faces += orient3d_filter(v[1] - p, v[2] - p, v[3] - p) == 0;
  }
  REQUIRE(disagree == 0);
  // Both answers occur (71,961 inside with libstdc++'s distributions), and
  // the filter leaves many faces open (367,479): the cases reach the exact
  // path (a face through the point, or nearly).
  CHECK(inside > kCases / 50);
  CHECK(kCases - inside > kCases / 20);
  CHECK(open_faces > kCases / 20);
}

TEST_CASE("perturbed segment-triangle: the inline filter answers as the exact path on a million near-degenerate cases",
          "[predicates]") {
  // segment_crosses_triangle_perturbed() lets orient3d's filter decide the
  // signs it can without a call, as the point-in-tet test does: compared
  // with the five signs from the expansion path alone. Integer triangles at
  // scales 2^-60 .. 2^60 with the segment through a vertex, through a point
  // of an edge, with an end on the triangle's plane (inside the triangle or
  // not: s a + t b + u c over 4), lying in that plane (the tie-break puts
  // both ends on one side: those try the ends' signs only), or with its ends
  // nudged by a unit off it; and double triangles with an end computed on
  // the plane in floating point and moved 0 .. 2 ulps a coordinate.
  std::mt19937_64 rng(28112026);
  std::uniform_int_distribution<std::int64_t> coord(-(std::int64_t(1) << 30), std::int64_t(1) << 30);
  std::uniform_int_distribution<std::int64_t> reach(-(std::int64_t(1) << 20), std::int64_t(1) << 20);
  std::uniform_int_distribution<std::int64_t> quarter(-2, 4), step(1, 3);
  std::uniform_int_distribution<int> kind(0, 5), nudge(-1, 1), ulps(-2, 2), exponent(-60, 60);
  std::uniform_real_distribution<double> u(-1.0, 1.0), w(-0.5, 1.5);
  constexpr int kCases = 1000000;
  int disagree = 0, crossing = 0;
  for (int i = 0; i < kCases; ++i) {
    std::array<Vec3, 3> t;
    Vec3 p, q;
    const int k = kind(rng);
    if (k < 5) {
      std::array<std::array<std::int64_t, 3>, 5> x{};  // a, b, c, p, q: integers
      for (int r = 0; r < 3; ++r)
        for (int a = 0; a < 3; ++a) x[r][a] = coord(rng) & ~std::int64_t(3);  // divisible by 4
      const std::int64_t s0 = quarter(rng), t0 = quarter(rng), s1 = quarter(rng), t1 = quarter(rng);
      const std::int64_t m = step(rng), n = step(rng);
      std::array<std::int64_t, 3> d{};
      for (std::int64_t& e : d) e = reach(rng);
      for (int a = 0; a < 3; ++a) {
        const auto on_plane = [&](std::int64_t ws, std::int64_t wt) {
          return (ws * x[0][a] + wt * x[1][a] + (4 - ws - wt) * x[2][a]) / 4;
        };
        switch (k) {
          case 0: x[3][a] = x[0][a] + m * d[a], x[4][a] = x[0][a] - n * d[a]; break;  // through vertex a
          case 1: {                                                                      // through a point of edge ab
            const std::int64_t e = (x[0][a] + 3 * x[1][a]) / 4;
            x[3][a] = e + m * d[a], x[4][a] = e - n * d[a];
            break;
          }
          case 2: x[3][a] = on_plane(s0, t0), x[4][a] = x[3][a] + d[a]; break;  // an end on the plane
          case 3: x[3][a] = on_plane(s0, t0), x[4][a] = on_plane(s1, t1); break;  // in the plane
          default: x[3][a] = on_plane(s0, t0) + nudge(rng), x[4][a] = on_plane(s1, t1) + nudge(rng); break;
        }
      }
      const double f = std::ldexp(1.0, exponent(rng));
      const auto at = [&](int r) { return Vec3(x[r][0] * f, x[r][1] * f, x[r][2] * f); };
      t = {at(0), at(1), at(2)};
      p = at(3), q = at(4);
    } else {
      const double f = std::ldexp(1.0, exponent(rng) / 2);
      for (Vec3& v : t) v = Vec3(u(rng), u(rng), u(rng)) * f;
      p = t[0] + w(rng) * (t[1] - t[0]) + w(rng) * (t[2] - t[0]);
      for (int a = 0; a < 3; ++a)
        for (int n = ulps(rng); n != 0; n += n > 0 ? -1 : 1) p[a] = std::nextafter(p[a], n > 0 ? HUGE_VAL : -HUGE_VAL);
      q = p + Vec3(u(rng), u(rng), u(rng)) * f;
    }
    const bool answer = segment_crosses_triangle_perturbed(p, q, t[0], t[1], t[2]);
    disagree += answer != reference_segment_crosses(p, q, t[0], t[1], t[2]);
    // The public edge sign, which the crossing test no longer calls.
    disagree += orient3d_perturbed_edge(p, q, t[0], t[1]) != reference_edge_side(p, q, t[0], t[1]);
    crossing += answer;
  }
  REQUIRE(disagree == 0);
  CHECK(crossing > kCases / 50);  // 160,677 cross with libstdc++'s distributions
  CHECK(kCases - crossing > kCases / 50);
}
