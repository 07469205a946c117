#include "sim/geometry/orient3d.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

namespace tcb {
namespace {

// ---- Expansion arithmetic (Shewchuk, "Adaptive Precision Floating-Point
// Arithmetic and Fast Robust Geometric Predicates", 1997). An expansion is a
// sum of non-overlapping doubles stored in increasing magnitude; its sign is
// the sign of its largest (last) component.

constexpr double kEpsilon = 0x1p-53;  // half an ulp of 1.0
constexpr double kSplitter = 0x1p27 + 1.0;
// Error bound of the filtered evaluation (orient3d "stage A").
constexpr double kOrient3dErrorBound = (7.0 + 56.0 * kEpsilon) * kEpsilon;
// Error bound of a 2x2 determinant of differences (orient2d "stage A").
constexpr double kDet2ErrorBound = (3.0 + 16.0 * kEpsilon) * kEpsilon;

// Capacity of the largest expansion formed below: a difference is 2 terms, a
// product of two differences 8, a 2x2 minor 16, a minor times a difference 64,
// the sum of three such terms 192.
constexpr std::size_t kMaxTerms = 192;

// Deliberately not zero-initialised: only term[0 .. size) is ever read, and
// clearing 1.5 KB per temporary dominated the degenerate (exact) path.
struct Expansion {
  std::array<double, kMaxTerms> term;
  std::size_t size = 0;
  Expansion() {}
  Expansion(const Expansion& other) : size(other.size) {
    std::copy(other.term.begin(), other.term.begin() + other.size, term.begin());
  }
  Expansion& operator=(const Expansion& other) {
    size = other.size;
    std::copy(other.term.begin(), other.term.begin() + other.size, term.begin());
    return *this;
  }
  void push_nonzero(double x) {
    if (x != 0.0) term[size++] = x;
  }
};

inline void two_sum(double a, double b, double& sum, double& err) {
  sum = a + b;
  const double b_virtual = sum - a;
  const double a_virtual = sum - b_virtual;
  err = (a - a_virtual) + (b - b_virtual);
}

inline void fast_two_sum(double a, double b, double& sum, double& err) {  // needs |a| >= |b|
  sum = a + b;
  err = b - (sum - a);
}

inline void split(double a, double& hi, double& lo) {
  const double c = kSplitter * a;
  hi = c - (c - a);
  lo = a - hi;
}

inline void two_product(double a, double b, double& product, double& err) {
  product = a * b;
  double a_hi, a_lo, b_hi, b_lo;
  split(a, a_hi, a_lo);
  split(b, b_hi, b_lo);
  err = a_lo * b_lo - (((product - a_hi * b_hi) - a_lo * b_hi) - a_hi * b_lo);
}

// Exact a - b as an expansion of at most two terms.
Expansion difference(double a, double b) {
  double s, e;
  two_sum(a, -b, s, e);
  Expansion r;
  r.push_nonzero(e);
  r.push_nonzero(s);
  return r;
}

// h = e * b (Scale-Expansion with zero elimination).
Expansion scale(const Expansion& e, double b) {
  Expansion h;
  if (e.size == 0 || b == 0.0) return h;
  double q, err;
  two_product(e.term[0], b, q, err);
  h.push_nonzero(err);
  for (std::size_t i = 1; i < e.size; ++i) {
    double p, p_err, sum, sum_err;
    two_product(e.term[i], b, p, p_err);
    two_sum(q, p_err, sum, sum_err);
    h.push_nonzero(sum_err);
    fast_two_sum(p, sum, q, sum_err);
    h.push_nonzero(sum_err);
  }
  h.push_nonzero(q);
  return h;
}

// h = e + f (Fast-Expansion-Sum with zero elimination; needs round-to-even).
Expansion sum(const Expansion& e, const Expansion& f) {
  if (e.size == 0) return f;
  if (f.size == 0) return e;
  // Merge both by increasing magnitude.
  std::array<double, kMaxTerms> g;
  std::size_t n = 0, i = 0, j = 0;
  while (i < e.size && j < f.size) {
    g[n++] = (std::fabs(e.term[i]) < std::fabs(f.term[j])) ? e.term[i++] : f.term[j++];
  }
  while (i < e.size) g[n++] = e.term[i++];
  while (j < f.size) g[n++] = f.term[j++];

  Expansion h;
  double q, err;
  fast_two_sum(g[1], g[0], q, err);
  h.push_nonzero(err);
  for (std::size_t k = 2; k < n; ++k) {
    double next;
    two_sum(q, g[k], next, err);
    h.push_nonzero(err);
    q = next;
  }
  h.push_nonzero(q);
  return h;
}

Expansion negate(Expansion e) {
  for (std::size_t i = 0; i < e.size; ++i) e.term[i] = -e.term[i];
  return e;
}

Expansion product(const Expansion& e, const Expansion& f) {
  Expansion result;
  for (std::size_t j = 0; j < f.size; ++j) result = sum(result, scale(e, f.term[j]));
  return result;
}

int sign_of(const Expansion& e) {
  if (e.size == 0) return 0;
  return e.term[e.size - 1] > 0.0 ? 1 : -1;
}

}  // namespace

int orient3d_exact(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                   const Eigen::Vector3d& d) {
  // det[a-d, b-d, c-d] = -det[b-a, c-a, d-a]; evaluated on exact differences.
  const Expansion adx = difference(a.x(), d.x()), ady = difference(a.y(), d.y()),
                  adz = difference(a.z(), d.z());
  const Expansion bdx = difference(b.x(), d.x()), bdy = difference(b.y(), d.y()),
                  bdz = difference(b.z(), d.z());
  const Expansion cdx = difference(c.x(), d.x()), cdy = difference(c.y(), d.y()),
                  cdz = difference(c.z(), d.z());
  const Expansion minor_a = sum(product(bdy, cdz), negate(product(bdz, cdy)));
  const Expansion minor_b = sum(product(cdy, adz), negate(product(cdz, ady)));
  const Expansion minor_c = sum(product(ady, bdz), negate(product(adz, bdy)));
  const Expansion det =
      sum(sum(product(adx, minor_a), product(bdx, minor_b)), product(cdx, minor_c));
  return -sign_of(det);
}

int orient3d(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
             const Eigen::Vector3d& d) {
  const double adx = a.x() - d.x(), ady = a.y() - d.y(), adz = a.z() - d.z();
  const double bdx = b.x() - d.x(), bdy = b.y() - d.y(), bdz = b.z() - d.z();
  const double cdx = c.x() - d.x(), cdy = c.y() - d.y(), cdz = c.z() - d.z();

  const double bdycdz = bdy * cdz, bdzcdy = bdz * cdy;
  const double cdyadz = cdy * adz, cdzady = cdz * ady;
  const double adybdz = ady * bdz, adzbdy = adz * bdy;
  const double det = adx * (bdycdz - bdzcdy) + bdx * (cdyadz - cdzady) + cdx * (adybdz - adzbdy);
  const double permanent = (std::fabs(bdycdz) + std::fabs(bdzcdy)) * std::fabs(adx) +
                           (std::fabs(cdyadz) + std::fabs(cdzady)) * std::fabs(bdx) +
                           (std::fabs(adybdz) + std::fabs(adzbdy)) * std::fabs(cdx);
  const double bound = kOrient3dErrorBound * permanent;
  if (det > bound) return -1;
  if (-det > bound) return 1;
  return orient3d_exact(a, b, c, d);
}

int cross_product_sign(const Eigen::Vector3d& from1, const Eigen::Vector3d& to1, const Eigen::Vector3d& from2,
                       const Eigen::Vector3d& to2, int axis) {
  const int j = (axis + 1) % 3, k = (axis + 2) % 3;
  const double u_j = to1[j] - from1[j], u_k = to1[k] - from1[k];
  const double v_j = to2[j] - from2[j], v_k = to2[k] - from2[k];
  const double left = u_j * v_k, right = u_k * v_j;
  const double det = left - right;
  const double bound = kDet2ErrorBound * (std::fabs(left) + std::fabs(right));
  if (det > bound) return 1;
  if (-det > bound) return -1;
  const Expansion exact = sum(product(difference(to1[j], from1[j]), difference(to2[k], from2[k])),
                              negate(product(difference(to1[k], from1[k]), difference(to2[j], from2[j]))));
  return sign_of(exact);
}

}  // namespace tcb
