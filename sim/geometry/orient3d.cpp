#include "sim/geometry/orient3d.hpp"

#include <algorithm>
#include <cmath>

namespace tcb {
namespace {

// ---- Expansion arithmetic (Shewchuk, "Adaptive Precision Floating-Point
// Arithmetic and Fast Robust Geometric Predicates", 1997). An expansion is a
// sum of non-overlapping doubles stored in increasing magnitude; its sign is
// the sign of its largest (last) component.

constexpr double kEpsilon = 0x1p-53;  // half an ulp of 1.0
constexpr double kSplitter = 0x1p27 + 1.0;
// Error bound of a 2x2 determinant of differences (orient2d "stage A").
constexpr double kDet2ErrorBound = (3.0 + 16.0 * kEpsilon) * kEpsilon;

// Capacity of the largest expansion formed below: a difference is 2 terms, a
// product of two differences 8, a 2x2 minor 16, a minor times a difference 64,
// the sum of three such terms 192.
constexpr int kMaxTerms = 192;

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

// The kernels below work on caller-owned arrays (no temporaries are copied:
// copying fixed-capacity expansion objects was a tenth of plates20's cycle).
// Each writes its result to h, which must not alias an input and must hold
// the stated number of terms, and returns the result's length; zero terms are
// eliminated, so an exactly zero value has length 0.

// h = a - b exactly; h holds 2 terms.
int difference(double a, double b, double* h) {
  double s, e;
  two_sum(a, -b, s, e);
  int n = 0;
  if (e != 0.0) h[n++] = e;
  if (s != 0.0) h[n++] = s;
  return n;
}

// h = e * b (Scale-Expansion with zero elimination); h holds 2 * elen terms.
int scale(int elen, const double* e, double b, double* h) {
  if (elen == 0 || b == 0.0) return 0;
  int n = 0;
  double q, err;
  two_product(e[0], b, q, err);
  if (err != 0.0) h[n++] = err;
  for (int i = 1; i < elen; ++i) {
    double p, p_err, s, s_err;
    two_product(e[i], b, p, p_err);
    two_sum(q, p_err, s, s_err);
    if (s_err != 0.0) h[n++] = s_err;
    fast_two_sum(p, s, q, s_err);
    if (s_err != 0.0) h[n++] = s_err;
  }
  if (q != 0.0) h[n++] = q;
  return n;
}

// h = e + f (Fast-Expansion-Sum with zero elimination; needs round-to-even):
// the terms of both, merged by increasing magnitude, summed in that order.
// h holds elen + flen terms.
int sum(int elen, const double* e, int flen, const double* f, double* h) {
  if (elen == 0 || flen == 0) {
    if (elen == 0) std::copy(f, f + flen, h);
    else std::copy(e, e + elen, h);
    return elen + flen;
  }
  int i = 0, j = 0, n = 0;
  const auto next = [&] {
    return (j == flen || (i < elen && std::fabs(e[i]) < std::fabs(f[j]))) ? e[i++] : f[j++];
  };
  double q = next(), err;
  fast_two_sum(next(), q, q, err);
  if (err != 0.0) h[n++] = err;
  while (i < elen || j < flen) {
    double s;
    two_sum(q, next(), s, err);
    if (err != 0.0) h[n++] = err;
    q = s;
  }
  if (q != 0.0) h[n++] = q;
  return n;
}

// h = sign * e * f for an f of at most 2 terms (a difference); sign is +1 or
// -1 (negation is exact). h holds 4 * elen terms.
int times_difference(int elen, const double* e, int flen, const double* f, double sign, double* h) {
  if (flen == 0) return 0;
  if (flen == 1) return scale(elen, e, sign * f[0], h);
  double low[kMaxTerms / 2], high[kMaxTerms / 2];
  const int nl = scale(elen, e, sign * f[0], low);
  const int nh = scale(elen, e, sign * f[1], high);
  return sum(nl, low, nh, high, h);
}

int sign_of(int n, const double* e) {
  if (n == 0) return 0;
  return e[n - 1] > 0.0 ? 1 : -1;
}

// h = e1 f1 - e2 f2 for four differences; h holds 16 terms.
int difference_of_products(int n_e1, const double* e1, int n_f1, const double* f1, int n_e2, const double* e2,
                           int n_f2, const double* f2, double* h) {
  double left[8], right[8];
  const int nl = times_difference(n_e1, e1, n_f1, f1, 1.0, left);
  const int nr = times_difference(n_e2, e2, n_f2, f2, -1.0, right);
  return sum(nl, left, nr, right, h);
}

// Whether each of the six terms of det[a; b; c] (rows (ax, ay, az), ...) has
// a factor that is exactly zero.
bool every_term_has_zero_factor(double ax, double ay, double az, double bx, double by, double bz, double cx,
                                double cy, double cz) {
  const auto zero = [](double x, double y, double z) { return x == 0.0 || y == 0.0 || z == 0.0; };
  return zero(ax, by, cz) && zero(ax, bz, cy) && zero(ay, bx, cz) && zero(ay, bz, cx) && zero(az, bx, cy) &&
         zero(az, by, cx);
}

// The summation stage's certificate: with S the sum of the 24 parts'
// magnitudes and A that sum as computed (S <= A (1 + 24 eps)), the sign of
// Sum2's result is the determinant's once |res| exceeds gamma(23)^2 S /
// (1 - 2 eps), which is below 529 eps^2 (1 + 100 eps) A (see the stage),
// under 2^10 eps^2 A.
constexpr double kSum2Bound = 0x1p-96;  // 2^10 eps^2
// Below this A the certificate is not tried: 2^-96 A is then normal, so the
// product is exact (a power of two). 2^-926 would do; this keeps a margin.
constexpr double kSmallestParts = 0x1p-900;

// After Sum2, up to this many further VecSum passes (for exact zeros).
constexpr int kMorePasses = 2;
// The smallest error sum the passes' certificate trusts: the product
// E (1 + 2^-47) is then normal and rounds relatively (the partial sums need
// nothing: below the normal range they add exactly).
constexpr double kSmallestCertified = 0x1p-1000;

// Two-Product, a b = p + e exactly: with a fused multiply-add, or Dekker's
// splitting. Exact when a b is a multiple of 2^-1074 (its lowest bit
// representable) and does not overflow: within orient3d's range contract
// every coordinate, so every difference, is a multiple of 2^-352 (0 or of
// magnitude at least about 1e-90), and every product of three of them, and
// each of its parts, a multiple of 2^-1056.
template <bool kFma>
inline void product_parts(double a, double b, double& p, double& e) {
  if constexpr (kFma) {
    p = a * b;
    e = __builtin_fma(a, b, -p);
  } else {
    two_product(a, b, p, e);
  }
}

template <bool kFma>
[[gnu::always_inline]] inline bool exact_differences_sign(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                                          const Eigen::Vector3d& c, const Eigen::Vector3d& d,
                                                          int& sign) {
  // The nine differences a-d, b-d, c-d; only exact ones go on (Two-Sum's
  // error is zero exactly when the rounded difference is the difference).
  double v[9];
  const Eigen::Vector3d* rows[3] = {&a, &b, &c};
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) {
      double err;
      two_sum((*rows[r])[k], -d[k], v[3 * r + k], err);
      if (err != 0.0) return false;
    }
  // det[a-d, b-d, c-d] by Leibniz: six signed products x y z of exact
  // differences (the sign put on x: negation is exact). Each is four doubles
  // exactly: y z = p + e, x p = P + E, x e = F + G, so the determinant is
  // the exact sum of t[24]. (This file is compiled without contraction of
  // a product into a later sum: every rounding here is the one written.)
  enum { AX, AY, AZ, BX, BY, BZ, CX, CY, CZ };
  static constexpr int kTerms[6][3] = {{AX, BY, CZ}, {AX, BZ, CY}, {BX, CY, AZ},
                                       {BX, CZ, AY}, {CX, AY, BZ}, {CX, AZ, BY}};
  double t[24];
  double parts = 0.0;  // A: the parts' magnitudes summed
  for (int i = 0; i < 6; ++i) {
    const double x = i % 2 == 0 ? v[kTerms[i][0]] : -v[kTerms[i][0]];
    double p, e;
    product_parts<kFma>(v[kTerms[i][1]], v[kTerms[i][2]], p, e);
    product_parts<kFma>(x, p, t[4 * i], t[4 * i + 1]);
    product_parts<kFma>(x, e, t[4 * i + 2], t[4 * i + 3]);
    for (int k = 0; k < 4; ++k) parts += std::fabs(t[4 * i + k]);
  }
  // Sum2 (Ogita, Rump and Oishi 2005, Algorithm 4.4): VecSum's chain of
  // Two-Sums leaves the rounded sum in t[23] and each step's error in the
  // slot before, the exact sum unchanged; res is t[23] plus the errors
  // summed. Their Proposition 4.5 (which holds with underflow too): for n
  // parts, |res - det| <= eps |det| + gamma(n-1)^2 S, gamma(m) = m eps /
  // (1 - m eps). With |det| <= |res| + err that gives err (1 - eps) <=
  // eps |res| + gamma(23)^2 S, so err < |res| (the sign is res's) whenever
  // |res| (1 - 2 eps) > gamma(23)^2 S; and gamma(23)^2 S (1 - 2 eps)^-1 <=
  // 529 eps^2 (1 + 100 eps) A < 2^-96 A.
  for (int i = 1; i < 24; ++i) two_sum(t[i - 1], t[i], t[i], t[i - 1]);
  double errors = 0.0, error_size = 0.0;
  for (int i = 0; i < 23; ++i) {
    errors += t[i];
    error_size += std::fabs(t[i]);
  }
  // orient3d's sign is the opposite of det[a-d, b-d, c-d]'s.
  if (error_size == 0.0) {  // no error left: the determinant is t[23], zero included
    sign = t[23] > 0.0 ? -1 : (t[23] < 0.0 ? 1 : 0);
    return true;
  }
  if (parts < kSmallestParts) return false;
  const double res = t[23] + errors;
  if (std::fabs(res) > kSum2Bound * parts) {
    sign = res > 0.0 ? -1 : 1;
    return true;
  }
  // Undecided: mostly an exact zero (coplanar points), which no bound can
  // certify. Further VecSum passes (each leaves the exact sum unchanged)
  // usually cancel the errors to nothing; or they become smaller than the
  // rounded sum, whose sign is then the determinant's: with E the errors'
  // magnitudes computed (E >= S (1 - eps)^22, partial sums normal or adding
  // exactly), |t[23]| > E (1 + 2^-47) rounded is above S.
  for (int pass = 0; pass < kMorePasses; ++pass) {
    for (int i = 1; i < 24; ++i) two_sum(t[i - 1], t[i], t[i], t[i - 1]);
    error_size = 0.0;
    for (int i = 0; i < 23; ++i) error_size += std::fabs(t[i]);
    if (error_size == 0.0) {
      sign = t[23] > 0.0 ? -1 : (t[23] < 0.0 ? 1 : 0);
      return true;
    }
    if (error_size < kSmallestCertified) return false;
    if (std::fabs(t[23]) > error_size * (1.0 + 64.0 * kEpsilon)) {
      sign = t[23] > 0.0 ? -1 : 1;
      return true;
    }
  }
  return false;
}

#if defined(__x86_64__) || defined(__i386__)
// The stage compiled for x86 processors with fused multiply-add (chosen at
// run time; the other build of it is exact too, with Dekker's products).
__attribute__((target("fma"))) bool exact_differences_sign_fma(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                                               const Eigen::Vector3d& c, const Eigen::Vector3d& d,
                                                               int& sign) {
  return exact_differences_sign<true>(a, b, c, d, sign);
}
#endif

}  // namespace

bool orient3d_exact_differences(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                const Eigen::Vector3d& d, int& sign, FusedMultiplyAdd fma) {
#if defined(__x86_64__) || defined(__i386__)
  if (fma == FusedMultiplyAdd::IfAvailable && __builtin_cpu_supports("fma"))
    return exact_differences_sign_fma(a, b, c, d, sign);
#else
  (void)fma;  // elsewhere Dekker's products (a target's own FMA flags would also do)
#endif
  return exact_differences_sign<false>(a, b, c, d, sign);
}

int orient3d_exact(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                   const Eigen::Vector3d& d) {
  // det[a-d, b-d, c-d] = -det[b-a, c-a, d-a]; evaluated on exact differences,
  // each a minor times a difference (the difference's at most 2 terms scale
  // the minor, rather than the minor's up to 16 terms scaling the difference).
  double diff[9][2];
  int n[9];
  const Eigen::Vector3d* rows[3] = {&a, &b, &c};
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) n[3 * r + k] = difference((*rows[r])[k], d[k], diff[3 * r + k]);
  enum { AX, AY, AZ, BX, BY, BZ, CX, CY, CZ };
  double minor_a[16], minor_b[16], minor_c[16];
  const int na = difference_of_products(n[BY], diff[BY], n[CZ], diff[CZ], n[BZ], diff[BZ], n[CY], diff[CY], minor_a);
  const int nb = difference_of_products(n[CY], diff[CY], n[AZ], diff[AZ], n[CZ], diff[CZ], n[AY], diff[AY], minor_b);
  const int nc = difference_of_products(n[AY], diff[AY], n[BZ], diff[BZ], n[AZ], diff[AZ], n[BY], diff[BY], minor_c);
  double term_a[64], term_b[64], term_c[64], ab[128], det[kMaxTerms];
  const int nta = times_difference(na, minor_a, n[AX], diff[AX], 1.0, term_a);
  const int ntb = times_difference(nb, minor_b, n[BX], diff[BX], 1.0, term_b);
  const int ntc = times_difference(nc, minor_c, n[CX], diff[CX], 1.0, term_c);
  const int nab = sum(nta, term_a, ntb, term_b, ab);
  return -sign_of(sum(nab, ab, ntc, term_c, det), det);
}

int orient3d(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
             const Eigen::Vector3d& d) {
  if (const int s = orient3d_filter(a - d, b - d, c - d); s != 0) return s;
  return orient3d_unfiltered(a, b, c, d);
}

int orient3d_unfiltered(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                        const Eigen::Vector3d& d) {
  const double adx = a.x() - d.x(), ady = a.y() - d.y(), adz = a.z() - d.z();
  const double bdx = b.x() - d.x(), bdy = b.y() - d.y(), bdz = b.z() - d.z();
  const double cdx = c.x() - d.x(), cdy = c.y() - d.y(), cdz = c.z() - d.z();
  // Exact shortcut: det is the sum of six products of three differences
  // (Leibniz); a computed difference is 0 exactly when its coordinates are
  // equal, so if every product has a zero factor the determinant is exactly 0.
  // This is the common degenerate case in scenes (faces in an axis-aligned
  // plane, points sharing coordinates), and it spares the expansion path.
  if (every_term_has_zero_factor(adx, ady, adz, bdx, bdy, bdz, cdx, cdy, cdz)) return 0;
  // Exact shortcut for two rows with a zero difference on one axis k (two of
  // a, b, c share d's k coordinate: a border edge's end and a surface edge in
  // one axis-aligned face, as where plates20's plates touch). The two rows'
  // cross product then has only its k component, so with m the third row,
  // det = r_m . (r_m+1 x r_m+2) (rows cyclic) = r_m[k] (r_m+1 x r_m+2)[k]:
  // the sign of one difference (a computed difference has the true one's
  // sign) times cross_product_sign(), exact, in place of the 3x3 stages.
  const double rows[3][3] = {{adx, ady, adz}, {bdx, bdy, bdz}, {cdx, cdy, cdz}};
  const Eigen::Vector3d* points[3] = {&a, &b, &c};
  for (int k = 0; k < 3; ++k) {
    const bool zero[3] = {rows[0][k] == 0.0, rows[1][k] == 0.0, rows[2][k] == 0.0};
    if (zero[0] + zero[1] + zero[2] != 2) continue;  // all three: the shortcut above answered
    const int m = !zero[0] ? 0 : (!zero[1] ? 1 : 2);
    const int minor = cross_product_sign(d, *points[(m + 1) % 3], d, *points[(m + 2) % 3], k);
    return rows[m][k] > 0.0 ? -minor : minor;  // orient3d's sign is the opposite of det's
  }
  int sign = 0;
  if (orient3d_exact_differences(a, b, c, d, sign)) return sign;
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
  // Exact shortcut, as in orient3d: both products have an exactly zero factor.
  if ((u_j == 0.0 || v_k == 0.0) && (u_k == 0.0 || v_j == 0.0)) return 0;
  return cross_product_sign_exact(from1, to1, from2, to2, axis);
}

int cross_product_sign_exact(const Eigen::Vector3d& from1, const Eigen::Vector3d& to1, const Eigen::Vector3d& from2,
                             const Eigen::Vector3d& to2, int axis) {
  const int j = (axis + 1) % 3, k = (axis + 2) % 3;
  double u_j[2], u_k[2], v_j[2], v_k[2], det[16];
  const int n_uj = difference(to1[j], from1[j], u_j), n_uk = difference(to1[k], from1[k], u_k);
  const int n_vj = difference(to2[j], from2[j], v_j), n_vk = difference(to2[k], from2[k], v_k);
  return sign_of(difference_of_products(n_uj, u_j, n_vk, v_k, n_uk, u_k, n_vj, v_j, det), det);
}

}  // namespace tcb
