#include "oracle/distance_oracle.hpp"

#include <cmath>
#include <limits>

namespace gjkdem::oracle {

std::vector<Vec3> minkowski_difference(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  std::vector<Vec3> d;
  for (const Vec3& p : a)
    for (const Vec3& q : b) d.push_back(p - q);
  return d;
}

Vec3 closest_on_triangle(const Vec3& a, const Vec3& b, const Vec3& c) {
  // The best of the three edges, and of the interior projection when it falls
  // strictly inside a well-shaped triangle (normal equations of the plane fit).
  auto seg = [](const Vec3& s, const Vec3& t) {
    const Vec3 d = t - s;
    const double dd = dot(d, d);
    double u = dd > 0 ? -dot(s, d) / dd : 0;
    u = u < 0 ? 0 : (u > 1 ? 1 : u);
    return s + d * u;
  };
  Vec3 best = seg(a, b);
  for (const Vec3& q : {seg(b, c), seg(c, a)})
    if (length_sq(q) < length_sq(best)) best = q;
  const Vec3 e1 = b - a, e2 = c - a;
  const double a11 = dot(e1, e1), a12 = dot(e1, e2), a22 = dot(e2, e2);
  const double det = a11 * a22 - a12 * a12;
  if (det > 1e-20 * a11 * a22) {
    const double r1 = -dot(a, e1), r2 = -dot(a, e2);
    const double s = (r1 * a22 - r2 * a12) / det, t = (a11 * r2 - a12 * r1) / det;
    if (s >= 0 && t >= 0 && s + t <= 1) {
      const Vec3 q = a + e1 * s + e2 * t;
      if (length_sq(q) < length_sq(best)) best = q;
    }
  }
  return best;
}

PairTruth brute_force_pair(const std::vector<Vec3>& d, double rel_tol) {
  double scale = 0;
  for (const Vec3& p : d) scale = std::fmax(scale, length(p));
  const double tol = rel_tol * (scale > 0 ? scale : 1);
  const int n = static_cast<int>(d.size());
  auto supports = [&](const Vec3& c) {  // every point satisfies p.c >= |c|^2
    const double cc = dot(c, c);
    const double len = std::sqrt(cc);
    for (const Vec3& p : d)
      if (dot(p, c) < cc - tol * len) return false;
    return true;
  };
  PairTruth t;
  // Separated: the closest point is on a vertex, edge or triangle with a supporting plane.
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < n; ++i)
    for (int j = i; j < n; ++j)
      for (int k = j; k < n; ++k) {
        const Vec3 c = closest_on_triangle(d[i], d[j], d[k]);
        const double cl = length(c);
        if (cl < best && cl > tol && supports(c)) { best = cl; t.closest = c; }
      }
  if (best < std::numeric_limits<double>::infinity()) {
    t.intersect = false;
    t.distance = best;
    return t;
  }
  // Intersecting: the depth is the nearest supporting plane through three points.
  t.intersect = true;
  best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      for (int k = j + 1; k < n; ++k) {
        Vec3 nrm = cross(d[j] - d[i], d[k] - d[i]);
        const double len = length(nrm);
        if (!(len > tol * scale)) continue;
        nrm /= len;
        double off = dot(nrm, d[i]);
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (const Vec3& p : d) { lo = std::fmin(lo, dot(nrm, p)); hi = std::fmax(hi, dot(nrm, p)); }
        if (hi <= off + tol) { /* outward normal nrm */ }
        else if (lo >= off - tol) { nrm = -nrm; off = -off; }
        else continue;
        if (off < best) { best = off; t.closest = nrm * off; }
      }
  t.depth = best < std::numeric_limits<double>::infinity() ? std::fmax(best, 0.0) : 0.0;
  return t;
}

}  // namespace gjkdem::oracle
