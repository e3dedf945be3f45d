#pragma once
// The boolean overlap test of the seed text's Algorithm 14, in 3D: add the
// support point in direction d; if it does not pass the origin (p.d < 0) a
// separating plane exists and the shapes are apart; otherwise replace the
// simplex by the feature nearest the origin with plane tests (the perpendicular
// ((B-A) x (O-A)) x (B-A) of the seed's walk-through, its triangle and
// tetrahedron analogues) and search on. No closest point is computed, which
// makes each iteration cheaper than the distance loop.
//
// Departures: a zero search direction (origin on the simplex: touching) counts
// as overlap, as the query format wants; a repeated support point or the
// iteration cap returns Undecided so the caller can fall back to the distance
// loop (gjk_impl.hpp), which is robust at the round-off floor.
#include "minkowski_diff.hpp"

namespace gjkdem::detail {

enum class Overlap { Separated, Intersecting, Undecided };

/// A tetrahedron of points of A - B that holds the origin: every face's
/// distance from the origin is a lower bound of the penetration depth.
struct Enclosure {
  Vec3 p[4];
  bool found = false;
};

/// `d` is the first search direction; `last_d` receives the last one (a
/// separating direction when the result is Separated), for warm starts.
/// `touch`: shapes closer than this touch (the distance loop's tolerance), so
/// a separating plane must clear it; one that does not leaves the pair
/// Undecided, and the distance loop answers as penetration() would.
/// `enclosure` (optional) receives the tetrahedron that holds the origin when
/// the answer is Intersecting by one (not by touching).
template <class MD>
Overlap gjk_boolean(MD& md, Vec3 d, int max_iterations, Real touch, int& iterations, Vec3& last_d,
                    Enclosure* enclosure = nullptr) noexcept {
  // p.d < 0 separates, unless within touch * |d| of 0: a touching contact.
  enum class Side { Separates, Touches, Passes };
  const auto side = [touch](const Vec3& p, const Vec3& dir) {
    const Real pd = dot(p, dir);
    if (pd >= 0) return Side::Passes;
    return pd * pd > touch * touch * dot(dir, dir) ? Side::Separates : Side::Touches;
  };
  if (!(dot(d, d) > 0)) d = {1, 0, 0};
  last_d = d;
  Vec3 s[4];  // s[n-1] is the newest point ("A" of the seed)
  int n = 0;
  s[n++] = md.support(d).w;
  if (const Side first = side(s[0], d); first != Side::Passes) {
    iterations = 1;
    return first == Side::Separates ? Overlap::Separated : Overlap::Undecided;
  }
  d = -s[0];
  for (iterations = 1; iterations <= max_iterations; ++iterations) {
    if (!(dot(d, d) > 0)) return Overlap::Intersecting;  // origin on the simplex
    last_d = d;
    const Vec3 p = md.support(d).w;
    if (const Side where = side(p, d); where != Side::Passes)  // Algorithm 14, line 5
      return where == Side::Separates ? Overlap::Separated : Overlap::Undecided;  // touching: the distance loop decides
    for (int k = 0; k < n; ++k)
      if (s[k] == p) return Overlap::Undecided;          // no progress: let the distance loop decide
    s[n++] = p;
    // newdirection(simplex): keep the feature whose region holds the origin.
    const Vec3 a = s[n - 1], ao = -a;
    if (n == 2) {
      const Vec3 ab = s[0] - a;
      if (dot(ab, ao) > 0) d = cross(cross(ab, ao), ab);
      else { s[0] = a; n = 1; d = ao; }
      continue;
    }
    if (n == 4) {
      // Tetrahedron (D, C, B, A): the origin is inside unless a face through A sees it.
      const Vec3 b = s[2], c = s[1], dd = s[0];
      const Vec3 abc = cross(b - a, c - a), acd = cross(c - a, dd - a), adb = cross(dd - a, b - a);
      // Orient each face normal away from the opposite vertex.
      const bool out_abc = dot(abc, ao) * dot(abc, dd - a) < 0 && dot(abc, ao) != 0;
      const bool out_acd = dot(acd, ao) * dot(acd, b - a) < 0 && dot(acd, ao) != 0;
      const bool out_adb = dot(adb, ao) * dot(adb, c - a) < 0 && dot(adb, ao) != 0;
      if (!out_abc && !out_acd && !out_adb) {
        if (enclosure) *enclosure = {{s[0], s[1], s[2], s[3]}, true};
        return Overlap::Intersecting;
      }
      if (out_abc) { s[0] = c; s[1] = b; }
      else if (out_acd) { s[0] = dd; s[1] = c; }
      else { s[0] = b; s[1] = dd; }
      s[2] = a;
      n = 3;
    }
    // Triangle (C, B, A).
    const Vec3 b = s[1], c = s[0];
    const Vec3 ab = b - a, ac = c - a, abc = cross(ab, ac);
    if (dot(cross(abc, ac), ao) > 0) {
      if (dot(ac, ao) > 0) { s[0] = c; s[1] = a; n = 2; d = cross(cross(ac, ao), ac); }
      else if (dot(ab, ao) > 0) { s[0] = b; s[1] = a; n = 2; d = cross(cross(ab, ao), ab); }
      else { s[0] = a; n = 1; d = ao; }
    } else if (dot(cross(ab, abc), ao) > 0) {
      if (dot(ab, ao) > 0) { s[0] = b; s[1] = a; n = 2; d = cross(cross(ab, ao), ab); }
      else { s[0] = a; n = 1; d = ao; }
    } else {
      d = dot(abc, ao) >= 0 ? abc : -abc;  // above or below the triangle
    }
  }
  return Overlap::Undecided;
}

}  // namespace gjkdem::detail
