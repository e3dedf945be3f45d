#pragma once
// Seeded pair families for the property tests of issue 12 (swap, scale and
// translation invariance of every query; overlap volume bounds): random
// polytopes, big near-spherical hulls, boxes (also with nearly parallel faces
// a hair apart), spheres, capsules and rounded cores, curved cores at size
// ratios 1e-2 to 1e2, small shapes sunk into the side of big curved ones,
// kinked maxima (coaxial and rim-to-rim cylinders, corners and apexes against
// rims) and one shape inside the other.
//
// Each family draws from its own std::mt19937_64 seed, so a family is the
// same whatever test runs first, and a failure names (family, index): the
// pair is rebuilt by calling the family's function and taking that index.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "gjkdem/shape/shape.hpp"
#include "gjkdem/shape/shape_factories.hpp"

namespace gjkdem::property {

struct Pair {
  Shape a, b;
  Vec3 ta, tb;  ///< world positions of the local origins
  Quat qa, qb;  ///< world orientations
  /// The normal and both witnesses are unique (a generic contact). False for
  /// face-against-face contacts (parallel faces, coaxial cylinders), where
  /// each witness may be any point of a patch: then the witnesses are
  /// checked as extreme points along the normal, not compared.
  bool unique = true;
  std::string what;  ///< one line: kinds and the parameters drawn
  Transform pose_a() const { return Transform::from(ta, qa); }
  Transform pose_b() const { return Transform::from(tb, qb); }
};

struct Family {
  std::string name;
  std::uint64_t seed = 0;
  std::vector<Pair> pairs;
  /// The family is meant to hold separated and intersecting pairs alike; the
  /// swap test checks the share of intersecting ones stays in [0.2, 0.8].
  bool mixed = true;
};

// ---------------------------------------------------------------- drawing

inline Real uniform(std::mt19937_64& rng, Real lo, Real hi) {
  return std::uniform_real_distribution<Real>(lo, hi)(rng);
}
inline Real log_uniform(std::mt19937_64& rng, Real lo, Real hi) {
  return std::exp(uniform(rng, std::log(lo), std::log(hi)));
}
inline Vec3 unit_vector(std::mt19937_64& rng) {
  std::normal_distribution<Real> g;
  for (;;) {
    const Vec3 d{g(rng), g(rng), g(rng)};
    if (length(d) > 1e-3) return normalized(d);
  }
}

/// Hull of n points drawn uniformly in a cube of edge `size` (interior points
/// drop out, so the hull has n or fewer vertices).
inline Shape cloud_polytope(std::mt19937_64& rng, int n, Real size) {
  std::vector<Vec3> pts;
  for (int i = 0; i < n; ++i)
    pts.push_back(Vec3{uniform(rng, -0.5, 0.5), uniform(rng, -0.5, 0.5), uniform(rng, -0.5, 0.5)} * size);
  return Shape{make_polytope(pts)};
}

/// Hull of n points on a sphere of the given radius, each radius jittered by
/// up to +-jitter (relative): a big, nearly round hull that hill-climbs.
inline Shape jittered_sphere(std::mt19937_64& rng, int n, Real radius, Real jitter) {
  std::vector<Vec3> pts;
  for (int i = 0; i < n; ++i) pts.push_back(unit_vector(rng) * (radius * (1 + uniform(rng, -jitter, jitter))));
  return Shape{make_polytope(pts)};
}

/// h_S(n): the support value of a placed shape along world direction n.
inline Real support_value(const Shape& s, const Transform& pose, const Vec3& n) {
  const Vec3 local = apply_inverse_rotation(pose, n);
  return dot(local, support(s, local)) + dot(n, pose.translation);
}

/// Places B so that its origin sits at A's origin + dir * f * D, where D is
/// the centre distance at which the slabs of A and B normal to dir just
/// touch: f > 1 is separated for sure, f < 1 mostly intersecting.
inline Vec3 place_along(const Shape& a, const Transform& pa, const Shape& b, const Quat& qb, const Vec3& dir, Real f) {
  const Transform rb = Transform::from({}, qb);
  const Real reach = support_value(a, pa, dir) - dot(dir, pa.translation) + support_value(b, rb, -dir);
  return pa.translation + dir * (f * reach);
}

// --------------------------------------------------------------- printing

inline std::string num(Real x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}
inline std::string num(const Vec3& v) { return "[" + num(v.x) + ", " + num(v.y) + ", " + num(v.z) + "]"; }
inline std::string num(const Quat& q) {
  return "[" + num(q.w) + ", " + num(q.x) + ", " + num(q.y) + ", " + num(q.z) + "]";
}

inline std::string describe(const Shape& s) {
  std::ostringstream o;
  std::visit(
      [&](const auto& c) {
        using T = std::decay_t<decltype(c)>;
        if constexpr (std::is_same_v<T, Point>)
          o << "point";
        else if constexpr (std::is_same_v<T, Segment>)
          o << "segment " << num(c.a) << " " << num(c.b);
        else if constexpr (std::is_same_v<T, Triangle>)
          o << "triangle " << num(c.v[0]) << num(c.v[1]) << num(c.v[2]);
        else if constexpr (std::is_same_v<T, Box>)
          o << "box half_extents " << num(c.half_extents);
        else if constexpr (std::is_same_v<T, Ellipsoid>)
          o << "ellipsoid radii " << num(c.radii);
        else if constexpr (std::is_same_v<T, Cylinder>)
          o << "cylinder r " << num(c.radius) << " hh " << num(c.half_height);
        else if constexpr (std::is_same_v<T, Cone>)
          o << "cone r " << num(c.radius) << " hh " << num(c.half_height);
        else if constexpr (std::is_same_v<T, Superellipsoid>)
          o << "superellipsoid radii " << num(c.radii) << " e1 " << num(c.e1) << " e2 " << num(c.e2);
        else {
          const auto& v = c.data->vertices;
          o << "polytope " << v.size() << " vertices";
          if (v.size() <= 12) {
            o << " {";
            for (const Vec3& p : v) o << num(p);
            o << "}";
          }
        }
      },
      s.core);
  if (s.margin > 0) o << " margin " << num(s.margin);
  return o.str();
}

inline std::string describe(const Pair& p) {
  return p.what + "\n  A: " + describe(p.a) + " at " + num(p.ta) + " q " + num(p.qa) + "\n  B: " + describe(p.b) +
         " at " + num(p.tb) + " q " + num(p.qb);
}

// --------------------------------------------------------------- families

/// Hulls of 4 to 64 random points, size 1, at random relative positions.
inline Family random_polytopes() {
  Family f{"RandomPolytopes", 1201, {}, true};
  std::mt19937_64 rng(f.seed);
  for (int i = 0; i < 40; ++i) {
    Pair p;
    const int na = 4 + static_cast<int>(uniform(rng, 0, 61)), nb = 4 + static_cast<int>(uniform(rng, 0, 61));
    p.a = cloud_polytope(rng, na, 1);
    p.b = cloud_polytope(rng, nb, 1);
    p.qa = random_rotation(rng);
    p.qb = random_rotation(rng);
    p.ta = Vec3{uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)};
    p.tb = place_along(p.a, p.pose_a(), p.b, p.qb, unit_vector(rng), uniform(rng, 0.55, 1.15));
    p.what = "clouds of " + std::to_string(na) + " and " + std::to_string(nb) + " points";
    f.pairs.push_back(p);
  }
  return f;
}

/// Hulls of 500 to 1000 points on a sphere of diameter 1 jittered by 1%:
/// big (hill-climbing) and nearly round, where EPA needs many faces.
inline Family near_spherical_hulls() {
  Family f{"NearSphericalHulls", 1202, {}, true};
  std::mt19937_64 rng(f.seed);
  std::vector<Shape> hulls;
  for (int n : {500, 700, 850, 1000}) hulls.push_back(jittered_sphere(rng, n, 0.5, 0.01));
  const int counts[4] = {500, 700, 850, 1000};
  for (int i = 0; i < 20; ++i) {
    Pair p;
    const int ia = i % 4, ib = (i / 4 + i) % 4;
    p.a = hulls[ia];
    p.b = hulls[ib];
    p.qa = random_rotation(rng);
    p.qb = random_rotation(rng);
    p.ta = Vec3{uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)};
    // Centres at least 0.35 diameters apart: deeper, the depth of two nearly
    // concentric near-spheres hardly depends on the direction (no unique normal).
    p.tb = place_along(p.a, p.pose_a(), p.b, p.qb, unit_vector(rng), uniform(rng, 0.4, 1.15));
    p.what = "jittered spheres of " + std::to_string(counts[ia]) + " and " + std::to_string(counts[ib]) + " points";
    f.pairs.push_back(p);
  }
  return f;
}

/// Boxes of half extents 0.05 to 0.6, random orientations (as boxes and as
/// 8-vertex polytopes).
inline Family boxes() {
  Family f{"Boxes", 1203, {}, true};
  std::mt19937_64 rng(f.seed);
  auto corners = [](const Vec3& h) {
    std::vector<Vec3> c;
    for (int k = 0; k < 8; ++k) c.push_back({k & 1 ? h.x : -h.x, k & 2 ? h.y : -h.y, k & 4 ? h.z : -h.z});
    return c;
  };
  for (int i = 0; i < 32; ++i) {
    Pair p;
    const Vec3 ha{uniform(rng, 0.05, 0.6), uniform(rng, 0.05, 0.6), uniform(rng, 0.05, 0.6)};
    const Vec3 hb{uniform(rng, 0.05, 0.6), uniform(rng, 0.05, 0.6), uniform(rng, 0.05, 0.6)};
    p.a = i % 4 == 3 ? Shape{make_polytope(corners(ha))} : Shape{Box{ha}};
    p.b = i % 4 == 2 ? Shape{make_polytope(corners(hb))} : Shape{Box{hb}};
    p.qa = random_rotation(rng);
    p.qb = random_rotation(rng);
    p.ta = Vec3{uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)};
    p.tb = place_along(p.a, p.pose_a(), p.b, p.qb, unit_vector(rng), uniform(rng, 0.55, 1.15));
    p.what = "boxes";
    f.pairs.push_back(p);
  }
  return f;
}

/// A small box tilted by 1e-9 to 1e-5 rad over the top face of a big one, a
/// gap of +-1e-8 x size (1e-8 apart, or overlapping by 1e-8), as boxes and
/// as polytopes, in both argument orders (FCL issue 388's setting). Face
/// against face: the witnesses are not unique.
inline Family parallel_faces() {
  Family f{"ParallelFaces", 1204, {}, true};
  std::mt19937_64 rng(f.seed);
  for (int i = 0; i < 32; ++i) {
    const Vec3 hb{uniform(rng, 0.3, 1.3), uniform(rng, 0.3, 1.3), uniform(rng, 0.01, 1)};
    const Vec3 hs{uniform(rng, 0.005, 0.05), uniform(rng, 0.005, 0.05), uniform(rng, 0.005, 0.05)};
    const Real tilt = log_uniform(rng, 1e-9, 1e-5), turn = uniform(rng, 0, 2 * kPi);
    const Quat q = quat_from_axis_angle({std::cos(turn), std::sin(turn), 0}, tilt);
    Real lowest = 1;
    for (int c = 0; c < 8; ++c)
      lowest = std::fmin(lowest, rotate(q, {c & 1 ? hs.x : -hs.x, c & 2 ? hs.y : -hs.y, c & 4 ? hs.z : -hs.z}).z);
    const Real size = 2 * length(hb);
    const Real gap = (i % 2 ? 1e-8 : -1e-8) * size;
    const Vec3 centre{uniform(rng, -1, 1) * (hb.x - 0.2), uniform(rng, -1, 1) * (hb.y - 0.2), hb.z + gap - lowest};
    // The whole setting turned and moved, so no face is axis-aligned in the world.
    const Quat turn_all = random_rotation(rng);
    const Vec3 shift{uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)};
    Shape small{Box{hs}}, big{Box{hb}};
    if (i % 4 >= 2) {
      std::vector<Vec3> cs, cb;
      for (int c = 0; c < 8; ++c) {
        cs.push_back({c & 1 ? hs.x : -hs.x, c & 2 ? hs.y : -hs.y, c & 4 ? hs.z : -hs.z});
        cb.push_back({c & 1 ? hb.x : -hb.x, c & 2 ? hb.y : -hb.y, c & 4 ? hb.z : -hb.z});
      }
      small = Shape{make_polytope(cs)};
      big = Shape{make_polytope(cb)};
    }
    Pair p;
    p.a = small;
    p.qa = turn_all * q;
    p.ta = shift + rotate(turn_all, centre);
    p.b = big;
    p.qb = turn_all;
    p.tb = shift;
    p.unique = false;
    p.what = std::string(i % 4 >= 2 ? "polytope" : "box") + " boxes, tilt " + num(tilt) + " rad, gap " +
             num(gap / size) + " x size";
    f.pairs.push_back(p);
  }
  return f;
}

/// Spheres (radius ratios 1e-2 to 1e2) against spheres, boxes and polytopes.
inline Family spheres() {
  Family f{"Spheres", 1205, {}, true};
  std::mt19937_64 rng(f.seed);
  for (int i = 0; i < 30; ++i) {
    Pair p;
    p.a = make_sphere(0.5);
    const Real rb = 0.5 * log_uniform(rng, 1e-2, 1e2);
    switch (i % 3) {
      case 0: p.b = make_sphere(rb); break;
      case 1: p.b = Shape{Box{Vec3{uniform(rng, 0.3, 1), uniform(rng, 0.3, 1), uniform(rng, 0.3, 1)} * rb}}; break;
      default: p.b = cloud_polytope(rng, 20, 2 * rb); break;
    }
    p.qa = random_rotation(rng);
    p.qb = random_rotation(rng);
    p.ta = Vec3{uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)};
    p.tb = place_along(p.a, p.pose_a(), p.b, p.qb, unit_vector(rng), uniform(rng, 0.55, 1.15));
    if (i % 2) std::swap(p.a, p.b), std::swap(p.ta, p.tb), std::swap(p.qa, p.qb);
    p.what = "sphere 0.5 against " +
             std::string(i % 3 == 0   ? "a sphere"
                         : i % 3 == 1 ? "a box"
                                      : "a polytope") +
             " of scale " + num(rb);
    f.pairs.push_back(p);
  }
  return f;
}

/// Capsules (segments with margins 0.02 to 0.3) against capsules, boxes and
/// polytopes; rounded boxes and rounded polytopes against each other.
inline Family capsules() {
  Family f{"Capsules", 1206, {}, true};
  std::mt19937_64 rng(f.seed);
  auto capsule = [&] {
    const Real half = uniform(rng, 0.1, 0.6);
    return make_capsule({-half, 0, 0}, {half, 0, 0}, uniform(rng, 0.02, 0.3));
  };
  for (int i = 0; i < 32; ++i) {
    Pair p;
    switch (i % 4) {
      case 0:
        p.a = capsule();
        p.b = capsule();
        p.what = "capsule, capsule";
        break;
      case 1:
        p.a = capsule();
        p.b = Shape{Box{{uniform(rng, 0.1, 0.5), uniform(rng, 0.1, 0.5), uniform(rng, 0.1, 0.5)}}};
        p.what = "capsule, box";
        break;
      case 2:
        p.a = Shape{Box{{uniform(rng, 0.1, 0.5), uniform(rng, 0.1, 0.5), uniform(rng, 0.1, 0.5)}},
                    uniform(rng, 0.01, 0.1)};
        p.b = cloud_polytope(rng, 12, 1);
        p.what = "rounded box, polytope";
        break;
      default: {
        Shape s = cloud_polytope(rng, 16, 0.8);
        s.margin = uniform(rng, 0.01, 0.1);
        p.a = s;
        p.b = capsule();
        p.what = "rounded polytope, capsule";
      }
    }
    p.qa = random_rotation(rng);
    p.qb = random_rotation(rng);
    p.ta = Vec3{uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)};
    p.tb = place_along(p.a, p.pose_a(), p.b, p.qb, unit_vector(rng), uniform(rng, 0.55, 1.15));
    f.pairs.push_back(p);
  }
  return f;
}

/// A random curved core (cylinder, cone, ellipsoid, superellipsoid) of the
/// given scale (about its bounding radius).
inline Shape curved_core(std::mt19937_64& rng, int kind, Real scale) {
  switch (kind % 4) {
    case 0: return Shape{Cylinder{scale * uniform(rng, 0.3, 0.7), scale * uniform(rng, 0.3, 0.7)}};
    case 1: return Shape{Cone{scale * uniform(rng, 0.3, 0.7), scale * uniform(rng, 0.3, 0.7)}};
    case 2: return Shape{Ellipsoid{Vec3{uniform(rng, 0.4, 1), uniform(rng, 0.4, 1), uniform(rng, 0.4, 1)} * scale}};
    default:
      return Shape{Superellipsoid{Vec3{uniform(rng, 0.4, 1), uniform(rng, 0.4, 1), uniform(rng, 0.4, 1)} * scale,
                                  uniform(rng, 0.3, 1.8), uniform(rng, 0.3, 1.8)}};
  }
}

/// Cylinders, cones, ellipsoids and superellipsoids against each other, B at
/// 1e-2 to 1e2 times A's size.
inline Family curved_size_ratios() {
  Family f{"CurvedSizeRatios", 1207, {}, true};
  std::mt19937_64 rng(f.seed);
  const char* names[4] = {"cylinder", "cone", "ellipsoid", "superellipsoid"};
  for (int i = 0; i < 48; ++i) {
    Pair p;
    const int ka = i % 4, kb = (i / 4) % 4;
    const Real ratio = log_uniform(rng, 1e-2, 1e2);
    p.a = curved_core(rng, ka, 1);
    p.b = curved_core(rng, kb, ratio);
    p.qa = random_rotation(rng);
    p.qb = random_rotation(rng);
    p.ta = Vec3{uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)};
    p.tb = place_along(p.a, p.pose_a(), p.b, p.qb, unit_vector(rng), uniform(rng, 0.6, 1.12));
    p.what = std::string(names[ka]) + " 1, " + names[kb] + " " + num(ratio);
    f.pairs.push_back(p);
  }
  return f;
}

/// A small cylinder, ellipsoid, box or cone (1e-2.5 to 1e-0.5 of the big one)
/// sunk into, or hovering over, the side of a big cone, cylinder or ellipsoid,
/// away from rims and apex (issue 12's first class).
inline Family sunk_into_side() {
  Family f{"SunkIntoSide", 1208, {}, true};
  std::mt19937_64 rng(f.seed);
  const char* big_names[3] = {"cone", "cylinder", "ellipsoid"};
  const char* small_names[4] = {"cylinder", "ellipsoid", "box", "cone"};
  for (int i = 0; i < 48; ++i) {
    const int kb = i % 3, ks = (i / 3) % 4;
    const Real scale = log_uniform(rng, 0.1, 3);
    const Real small = scale * log_uniform(rng, std::pow(10.0, -2.5), std::pow(10.0, -0.5));
    Shape s;
    switch (ks) {
      case 0: s = Shape{Cylinder{small * uniform(rng, 0.5, 1.5), small * uniform(rng, 0.5, 1.5)}}; break;
      case 1:
        s = Shape{Ellipsoid{Vec3{uniform(rng, 0.5, 1.5), uniform(rng, 0.5, 1.5), uniform(rng, 0.5, 1.5)} * small}};
        break;
      case 2:
        s = Shape{Box{Vec3{uniform(rng, 0.5, 1.5), uniform(rng, 0.5, 1.5), uniform(rng, 0.5, 1.5)} * small}};
        break;
      default: s = Shape{Cone{small * uniform(rng, 0.5, 1.5), small * uniform(rng, 0.5, 1.5)}}; break;
    }
    const Real reach = bounding_radius(s);
    Shape big;
    Vec3 side, normal;
    const Real phi = uniform(rng, 0, 2 * kPi);
    if (kb == 0) {  // cone: radius 2 scale, half height scale
      const Real radius = 2 * scale, hh = scale;
      big = Shape{Cone{radius, hh}};
      const Real z = -hh + 2 * reach + (2 * hh - 4 * reach) * uniform(rng, 0.15, 0.85);
      const Real r = radius * (hh - z) / (2 * hh);
      side = {r * std::cos(phi), r * std::sin(phi), z};
      normal = normalized(Vec3{2 * hh * std::cos(phi), 2 * hh * std::sin(phi), radius});
    } else if (kb == 1) {  // cylinder: radius scale, half height 1.5 scale
      big = Shape{Cylinder{scale, 1.5 * scale}};
      const Real z = uniform(rng, -0.7, 0.7) * 1.5 * scale;
      side = {scale * std::cos(phi), scale * std::sin(phi), z};
      normal = {std::cos(phi), std::sin(phi), 0};
    } else {  // ellipsoid
      const Vec3 radii = Vec3{uniform(rng, 0.6, 1.4), uniform(rng, 0.6, 1.4), uniform(rng, 0.6, 1.4)} * scale;
      big = Shape{Ellipsoid{radii}};
      const Vec3 u = unit_vector(rng);
      side = hadamard(radii, u);
      normal = normalized(Vec3{u.x / radii.x, u.y / radii.y, u.z / radii.z});
    }
    // Negative sinks hover: separated by a fraction of the small shape.
    const Real sink = reach * (i % 4 == 3 ? -uniform(rng, 0.05, 0.6) : uniform(rng, 0.05, 0.95));
    Pair p;
    const Quat turn_all = random_rotation(rng);
    p.a = s;
    p.qa = turn_all * random_rotation(rng);
    p.ta = rotate(turn_all, side - normal * sink);
    p.b = big;
    p.qb = turn_all;
    p.tb = {};
    if (i % 2) std::swap(p.a, p.b), std::swap(p.ta, p.tb), std::swap(p.qa, p.qb);
    p.what = std::string(small_names[ks]) + " " + num(small) + " sunk " + num(sink) + " into a " + big_names[kb] + " " +
             num(scale) + (i % 2 ? " (big first)" : " (small first)");
    f.pairs.push_back(p);
  }
  f.mixed = false;  // three in four sunk
  return f;
}

/// A corner (box, polytope vertex, cone apex, cylinder rim, a bare point)
/// 1e-12, 1e-9 or 1e-6 x size off the curved side of a cylinder, cone or
/// ellipsoid, or 1e-9 x size into it: cores nearly touching where GJK
/// converges only linearly.
inline Family near_touching_curved() {
  Family f{"NearTouchingCurved", 1211, {}, true};
  std::mt19937_64 rng(f.seed);
  const char* big_names[3] = {"cylinder", "cone", "ellipsoid"};
  const char* small_names[5] = {"box", "polytope", "cone", "cylinder", "point"};
  const Real gaps[4] = {1e-12, 1e-9, 1e-6, -1e-9};
  for (int i = 0; i < 40; ++i) {
    const int kb = i % 3, ks = (i / 3) % 5;
    Shape big;
    Vec3 side, normal;
    const Real phi = uniform(rng, 0, 2 * kPi);
    if (kb == 0) {
      const Real r = uniform(rng, 0.3, 0.6), hh = uniform(rng, 0.3, 0.6);
      big = Shape{Cylinder{r, hh}};
      side = {r * std::cos(phi), r * std::sin(phi), uniform(rng, -0.6, 0.6) * hh};
      normal = {std::cos(phi), std::sin(phi), 0};
    } else if (kb == 1) {
      const Real radius = uniform(rng, 0.3, 0.6), hh = uniform(rng, 0.3, 0.6);
      big = Shape{Cone{radius, hh}};
      const Real z = hh * uniform(rng, -0.6, 0.4);
      const Real r = radius * (hh - z) / (2 * hh);
      side = {r * std::cos(phi), r * std::sin(phi), z};
      normal = normalized(Vec3{2 * hh * std::cos(phi), 2 * hh * std::sin(phi), radius});
    } else {
      const Vec3 radii{uniform(rng, 0.3, 0.6), uniform(rng, 0.3, 0.6), uniform(rng, 0.3, 0.6)};
      big = Shape{Ellipsoid{radii}};
      const Vec3 u = unit_vector(rng);
      side = hadamard(radii, u);
      normal = normalized(Vec3{u.x / radii.x, u.y / radii.y, u.z / radii.z});
    }
    Shape small;
    switch (ks) {
      case 0: small = Shape{Box{{uniform(rng, 0.02, 0.15), uniform(rng, 0.02, 0.15), uniform(rng, 0.02, 0.15)}}}; break;
      case 1: small = cloud_polytope(rng, 10, 0.2); break;
      case 2: small = Shape{Cone{uniform(rng, 0.02, 0.15), uniform(rng, 0.02, 0.15)}}; break;
      case 3: small = Shape{Cylinder{uniform(rng, 0.02, 0.15), uniform(rng, 0.02, 0.15)}}; break;
      default: small = Shape{Point{}}; break;
    }
    const Real size = 2 * std::fmax(bounding_radius(big), bounding_radius(small));
    const Real gap = gaps[(i / 15 + i) % 4] * size;
    Pair p;
    const Quat turn_all = random_rotation(rng);
    const Quat qs = random_rotation(rng);
    // The corner towards the side (the small shape's support point along -normal) placed at side + gap * normal.
    const Vec3 corner = rotate(qs, support(small, rotate(conjugate(qs), -normal)));
    p.a = small;
    p.qa = turn_all * qs;
    p.ta = rotate(turn_all, side + normal * gap - corner);
    p.b = big;
    p.qb = turn_all;
    p.tb = {};
    if (i % 2) std::swap(p.a, p.b), std::swap(p.ta, p.tb), std::swap(p.qa, p.qb);
    p.what = std::string(small_names[ks]) + " corner " + num(gap / size) + " x size off a " + big_names[kb] +
             "'s side" + (i % 2 ? " (curved first)" : " (corner first)");
    f.pairs.push_back(p);
  }
  return f;
}

/// Depth minima at kinks: coaxial cylinders (issue 12's second class),
/// cylinders rim to rim, a box corner and a cone apex against a cylinder rim,
/// cones apex to apex.
inline Family kinked_maxima() {
  Family f{"KinkedMaxima", 1209, {}, true};
  std::mt19937_64 rng(f.seed);
  for (int i = 0; i < 48; ++i) {
    Pair p;
    const Quat q = random_rotation(rng);
    const Vec3 centre{uniform(rng, -0.5, 0.5), uniform(rng, -0.5, 0.5), uniform(rng, -0.5, 0.5)};
    p.qa = q;
    p.ta = centre;
    switch (i % 4) {
      case 0: {  // coaxial cylinders, as tests/collide/coaxial_cylinders_test.cpp
        const Real ra = uniform(rng, 0.2, 1), ha = uniform(rng, 0.2, 1), rb = uniform(rng, 0.2, 1),
                   hb = uniform(rng, 0.2, 1);
        const Real radial = (i / 4) % 2 ? 0.9 * uniform(rng, 0, 1) * (ra + rb) : 0;
        const Real axial = (i / 4) % 3 ? uniform(rng, -0.9, 0.9) * (ha + hb) : 0;
        const Real turn = uniform(rng, 0, 2 * kPi);
        p.a = Shape{Cylinder{ra, ha}};
        p.b = Shape{Cylinder{rb, hb}};
        p.qb = q;
        p.tb = centre + rotate(q, {radial * std::cos(turn), radial * std::sin(turn), axial});
        p.unique = false;  // caps face to face; without a radial offset any radial normal
        p.what = "coaxial cylinders, radial " + num(radial) + " axial " + num(axial);
        break;
      }
      case 1: {  // rims crossing: parallel-ish axes, offsets near the sums
        const Real ra = uniform(rng, 0.2, 1), ha = uniform(rng, 0.2, 1), rb = uniform(rng, 0.2, 1),
                   hb = uniform(rng, 0.2, 1);
        const Real tilt = log_uniform(rng, 1e-3, 1e-1), turn = uniform(rng, 0, 2 * kPi);
        const Real radial = (ra + rb) * uniform(rng, 0.85, 1.05), axial = (ha + hb) * uniform(rng, 0.85, 1.05);
        p.a = Shape{Cylinder{ra, ha}};
        p.b = Shape{Cylinder{rb, hb}};
        p.qb = q * quat_from_axis_angle({std::cos(turn + 1), std::sin(turn + 1), 0}, tilt);
        p.tb = centre + rotate(q, {radial * std::cos(turn), radial * std::sin(turn), axial});
        p.what = "cylinders rim to rim, tilt " + num(tilt);
        break;
      }
      case 2: {  // a box corner or a cone apex against a cylinder's rim
        const Real r = uniform(rng, 0.3, 1), h = uniform(rng, 0.3, 1), turn = uniform(rng, 0, 2 * kPi);
        p.a = Shape{Cylinder{r, h}};
        const bool cone = (i / 4) % 2;
        p.b = cone ? Shape{Cone{uniform(rng, 0.1, 0.4), uniform(rng, 0.1, 0.4)}}
                   : Shape{Box{{uniform(rng, 0.05, 0.3), uniform(rng, 0.05, 0.3), uniform(rng, 0.05, 0.3)}}};
        const Vec3 rim{r * std::cos(turn), r * std::sin(turn), h};
        const Vec3 out = normalized(Vec3{std::cos(turn), std::sin(turn), 0} + Vec3{0, 0, 1} * uniform(rng, 0.3, 3) +
                                    unit_vector(rng) * 0.2);
        // B's extreme point towards the rim: a corner, or the apex pointing at it.
        const Quat qb_local = cone ? Quat{} : random_rotation(rng);
        Quat qb = qb_local;
        if (cone) {  // turn the cone's +z (apex) onto -out
          const Vec3 axis = cross(Vec3{0, 0, 1}, -out);
          const Real angle = std::atan2(length(axis), dot(Vec3{0, 0, 1}, -out));
          qb = length(axis) > 0 ? quat_from_axis_angle(normalized(axis), angle) : Quat{};
        }
        const Real reach = support_value(p.b, Transform::from({}, qb), -out);
        const Real push = reach * uniform(rng, 0.85, 1.05);  // < 1: the tip sinks into the rim
        p.qb = q * qb;
        p.tb = centre + rotate(q, rim + out * push);
        p.what = std::string(cone ? "cone apex" : "box corner") + " at a cylinder rim, push " + num(push / reach);
        break;
      }
      default: {  // cones apex to apex, axes nearly opposed
        const Real ra = uniform(rng, 0.2, 0.8), ha = uniform(rng, 0.2, 0.8), rb = uniform(rng, 0.2, 0.8),
                   hb = uniform(rng, 0.2, 0.8);
        p.a = Shape{Cone{ra, ha}};
        p.b = Shape{Cone{rb, hb}};
        const Real tilt = uniform(rng, 0.05, 0.6);
        p.qb = q * quat_from_axis_angle(normalized(Vec3{uniform(rng, -1, 1), uniform(rng, -1, 1), 0}), kPi - tilt);
        const Real axial = (ha + hb) * uniform(rng, 0.9, 1.05);
        p.tb = centre + rotate(q, Vec3{uniform(rng, -0.1, 0.1), uniform(rng, -0.1, 0.1), axial});
        p.what = "cones apex to apex, tilt " + num(tilt) + " axial " + num(axial / (ha + hb)) + " x (ha + hb)";
      }
    }
    f.pairs.push_back(p);
  }
  return f;
}

/// One shape inside the other (well inside: its bounding ball fits in the
/// outer shape's inscribed ball, off centre): small boxes, polytopes,
/// spheres, ellipsoids, capsules, cones in big boxes, polytopes, ellipsoids,
/// cylinders, spheres and near-spherical hulls, at ratios 1e-2 to 0.3.
inline Family containment() {
  Family f{"Containment", 1210, {}, false};
  std::mt19937_64 rng(f.seed);
  std::vector<Vec3> octa = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int i = 0; i < 36; ++i) {
    const int ko = i % 6, ki = (i / 6) % 6;
    Shape outer;
    Real inradius = 0;  // radius of a ball about the origin inside the outer shape
    switch (ko) {
      case 0: {
        const Vec3 h{uniform(rng, 0.5, 1), uniform(rng, 0.5, 1), uniform(rng, 0.5, 1)};
        outer = Shape{Box{h}};
        inradius = std::fmin(h.x, std::fmin(h.y, h.z));
        break;
      }
      case 1: {
        std::vector<Vec3> pts = octa;  // an octahedron (inradius 1/sqrt 3) and random points inside
        for (int k = 0; k < 20; ++k)
          pts.push_back(Vec3{uniform(rng, -0.3, 0.3), uniform(rng, -0.3, 0.3), uniform(rng, -0.3, 0.3)});
        outer = Shape{make_polytope(pts)};
        inradius = 1 / std::sqrt(3.0);
        break;
      }
      case 2: {
        const Vec3 r{uniform(rng, 0.5, 1), uniform(rng, 0.5, 1), uniform(rng, 0.5, 1)};
        outer = Shape{Ellipsoid{r}};
        inradius = std::fmin(r.x, std::fmin(r.y, r.z));
        break;
      }
      case 3: {
        const Real r = uniform(rng, 0.5, 1), h = uniform(rng, 0.5, 1);
        outer = Shape{Cylinder{r, h}};
        inradius = std::fmin(r, h);
        break;
      }
      case 4: {
        const Real r = uniform(rng, 0.5, 1);
        outer = make_sphere(r);
        inradius = r;
        break;
      }
      default:
        outer = jittered_sphere(rng, 600, 1, 0.01);
        inradius = 0.98 * std::cos(0.2);
        break;  // facets of ~0.2 rad
    }
    const Real ratio = log_uniform(rng, 1e-2, 0.3);
    const Real s = ratio * inradius;
    Shape inner;
    switch (ki) {
      case 0:
        inner = Shape{Box{Vec3{uniform(rng, 0.3, 0.57), uniform(rng, 0.3, 0.57), uniform(rng, 0.3, 0.57)} * s}};
        break;
      case 1: inner = cloud_polytope(rng, 12, s); break;
      case 2: inner = make_sphere(s * uniform(rng, 0.5, 1)); break;
      case 3:
        inner = Shape{Ellipsoid{Vec3{uniform(rng, 0.5, 1), uniform(rng, 0.5, 1), uniform(rng, 0.5, 1)} * s}};
        break;
      case 4: inner = make_capsule({-0.5 * s, 0, 0}, {0.5 * s, 0, 0}, 0.4 * s); break;
      default: inner = Shape{Cone{0.6 * s, 0.6 * s}}; break;
    }
    // The inner shape's centre anywhere in the ball of radius inradius - its reach.
    const Real room = inradius - bounding_radius(inner);
    const Vec3 at = unit_vector(rng) * (room * std::cbrt(uniform(rng, 0.05, 0.95)));
    Pair p;
    p.qa = random_rotation(rng);
    p.ta = Vec3{uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)};
    p.a = outer;
    p.b = inner;
    p.qb = random_rotation(rng);
    p.tb = apply(p.pose_a(), at);
    if (i % 2) std::swap(p.a, p.b), std::swap(p.ta, p.tb), std::swap(p.qa, p.qb);
    const char* outer_names[6] = {"box",      "octahedron hull", "ellipsoid",
                                  "cylinder", "sphere",          "600-point jittered sphere"};
    const char* inner_names[6] = {"box", "polytope", "sphere", "ellipsoid", "capsule", "cone"};
    p.what = std::string(inner_names[ki]) + " inside a " + outer_names[ko] + " (ratio " + num(ratio) + ")" +
             (i % 2 ? " (inner first)" : " (outer first)");
    f.pairs.push_back(p);
  }
  return f;
}

}  // namespace gjkdem::property
