// Issue 12's property tests: every query (intersect, distance, penetration)
// gives the mirrored answer when A and B are swapped, the same answer scaled
// under a uniform scale from 1e-4 to 1e4, and the same answer under a common
// translation by (1e6, -1e6, 1e6), on every pair family of
// property_families.hpp.
//
// Tolerances come from the settings (tolerances.hpp), never from what the
// code happens to achieve:
//  - a separated answer that GJK ended by its duality gap is within
//    kGjkRelTol x (core distance) + kGjkAbsTol x size of the truth;
//  - a depth that EPA ended by its gap (status Converged) on polytope-like
//    cores is within kEpaRelTol x depth + kEpaAbsTol x size;
//  - an answer that did not converge (EPA OutOfMemory or MaxIterations, GJK
//    MaxIterations) and any depth of a curved core (the polish reports
//    Converged whether or not it reached the minimum) is held to the query
//    format's accuracy, 1e-6 x value + 1e-9 x size (docs/tolerances.md);
//  - two answers that should agree may differ by the sum of their errors.
// Normals: for separated pairs the closest point v* of A - B is unique and,
// by convexity, |v - v*|^2 <= |v|^2 - |v*|^2 ~ 2 d delta for a point v of A -
// B at most delta longer, so the directions differ by at most sqrt(2 delta /
// d) (see finish()). For intersecting pairs the minimiser of the depth need
// not be unique, so each answer's normal must achieve the other's depth
// within the errors; the angle is compared too on generic pairs (Pair::unique).
// Witnesses: compared on generic pairs; everywhere each answer's witnesses
// must lie in their shapes at the extremes along its normal (check_contract),
// to the format's witness accuracy (see kFormatWitnessTol).
// The 1e6 translation: see kOffsetRoundOff.
#include "gjkdem/collide/query.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "collide/property_families.hpp"

namespace gjkdem {
namespace {

using property::Family;
using property::num;
using property::Pair;
using property::support_value;

constexpr Real kEps = std::numeric_limits<Real>::epsilon();
/// Round-off of one query on coordinates of order `size` (a rotation, a
/// subtraction, a simplex solve, the margins): 64 ulps of the size, far below
/// kGjkAbsTol x size (450 ulps), so it never decides a check on its own.
constexpr Real kRoundOff = 64 * kEps;
/// The query format's accuracy (docs/tolerances.md, ../shared/tools/check-pairs):
/// what answers that did not converge to the settings' tolerances are held
/// to: values to 1e-6 relative plus 1e-9 x size, normals to 1e-4 rad.
constexpr Real kFormatRelTol = 1e-6, kFormatAbsTol = 1e-9, kFormatAngle = 1e-4;

const Real kScales[] = {1e-4, 1e-2, 1e2, 1e4};
const Vec3 kOffset{1e6, -1e6, 1e6};
/// A common translation T moves nothing relative, but each pose's translation
/// t + T is rounded to half an ulp of 1e6 (2^-34 ~ 5.8e-11) per coordinate, so
/// B's position relative to A moves by up to sqrt(3) ulp(1e6) ~ 2e-10.
/// Distance and depth are 1-Lipschitz in that position, and witnesses come
/// back through one more rounding at 1e6 (subtracting T again is exact), so
/// 4 ulp(1e6) ~ 4.7e-10 bounds what the offset alone may change: about 1e-9
/// for unit shapes, as issue 12 expects.
const Real kOffsetRoundOff = 4 * (std::nextafter(1e6, 2e6) - 1e6);

bool curved(const Shape& s) {
  return std::holds_alternative<Cylinder>(s.core) || std::holds_alternative<Cone>(s.core) ||
         std::holds_alternative<Ellipsoid>(s.core) || std::holds_alternative<Superellipsoid>(s.core);
}

/// A placed pair: a family's pair in one argument order, possibly scaled and
/// translated.
struct Config {
  Shape a, b;
  Transform pa, pb;
  Real size = 0;  ///< as the queries measure it: the larger bounding diameter
};

Config make_config(const Pair& p, bool swapped, Real scale = 1, const Vec3& offset = {}) {
  Config c;
  const Transform pa = p.pose_a(), pb = p.pose_b();
  auto place = [&](const Transform& t) { return Transform{t.rotation, t.translation * scale + offset}; };
  const Shape a = scale == 1 ? p.a : scaled(p.a, scale), b = scale == 1 ? p.b : scaled(p.b, scale);
  c.a = swapped ? b : a;
  c.b = swapped ? a : b;
  c.pa = place(swapped ? pb : pa);
  c.pb = place(swapped ? pa : pb);
  c.size = 2 * std::fmax(bounding_radius(c.a), bounding_radius(c.b));
  return c;
}

/// One query's answer, the parts the properties compare.
struct Answer {
  bool intersect = false;
  bool has_vectors = false;  ///< normal and witnesses set (distance() leaves them out when intersecting)
  Real value = 0;            ///< distance, or depth when intersecting
  Vec3 normal, wa, wb;
  Real error = 0;        ///< what the settings promise for value (length)
  Real angle_error = 0;  ///< what they imply for the normal (rad)
  std::string status;
};

Real gjk_error(Real core_distance, Real size) {
  const QuerySettings st;
  return st.gjk_rel_tol * core_distance + st.gjk_abs_tol * size + kRoundOff * size;
}
Real format_error(Real value, Real size) { return kFormatRelTol * value + kFormatAbsTol * size; }

const char* name(GjkStatus s) {
  switch (s) {
    case GjkStatus::Separated: return "Separated";
    case GjkStatus::Intersecting: return "Intersecting";
    default: return "MaxIterations";
  }
}
const char* name(EpaStatus s) {
  switch (s) {
    case EpaStatus::NotRun: return "NotRun";
    case EpaStatus::Converged: return "Converged";
    case EpaStatus::Touching: return "Touching";
    case EpaStatus::Degenerate: return "Degenerate";
    case EpaStatus::OutOfMemory: return "OutOfMemory";
    default: return "MaxIterations";
  }
}

/// The normal's accuracy implied by the value's: for a separated pair the
/// closest point v* of A - B is unique and, by convexity, any point v of A - B
/// at most e longer has |v - v*|^2 <= |v|^2 - |v*|^2 ~ 2 d e, so the normals
/// differ by at most sqrt(2 e / d). The same bound is taken for depths
/// (assuming the boundary of A - B curves no tighter than the depth there).
/// Answers held to the format get the format's 1e-4 rad.
void finish(Answer& r, bool format) {
  r.angle_error = format ? kFormatAngle : r.value > 0 ? std::sqrt(2 * r.error / r.value) : 4;
}

Answer distance_answer(const Config& c) {
  const DistanceResult r = distance(c.a, c.pa, c.b, c.pb);
  Answer out;
  out.intersect = r.intersect;
  out.has_vectors = !r.intersect;
  out.value = r.distance;
  out.normal = r.normal;
  out.wa = r.witness_a;
  out.wb = r.witness_b;
  const Real margins = c.a.margin + c.b.margin;
  const bool format = r.status == GjkStatus::MaxIterations;
  out.error = format ? format_error(r.distance, c.size) : gjk_error(r.distance + margins, c.size);
  finish(out, format);
  out.status = std::string("distance/") + name(r.status);
  return out;
}

Answer penetration_answer(const Config& c) {
  const PenetrationResult r = penetration(c.a, c.pa, c.b, c.pb);
  const QuerySettings st;
  Answer out;
  out.intersect = r.intersect;
  out.has_vectors = true;
  out.value = r.intersect ? r.depth : r.distance;
  out.normal = r.normal;
  out.wa = r.witness_a;
  out.wb = r.witness_b;
  const Real margins = c.a.margin + c.b.margin;
  bool format = false;
  if (r.gjk_status != GjkStatus::Intersecting) {  // cores apart: GJK alone (depth within the margins)
    format = r.gjk_status == GjkStatus::MaxIterations;
    out.error = format ? format_error(out.value, c.size) : gjk_error(margins + r.distance, c.size);
  } else if (curved(c.a) || curved(c.b)) {
    format = true;
  } else {
    switch (r.epa_status) {
      case EpaStatus::Converged:
        out.error = st.epa_rel_tol * r.depth + st.epa_abs_tol * c.size + kRoundOff * c.size;
        break;
      case EpaStatus::Touching: out.error = st.touch_tol * c.size + kRoundOff * c.size; break;
      case EpaStatus::Degenerate: out.error = kRoundOff * c.size; break;
      default: format = true;
    }
  }
  if (format) out.error = format_error(out.value, c.size);
  finish(out, format);
  out.status = std::string("penetration/") + name(r.gjk_status) + "/" + name(r.epa_status);
  return out;
}

/// Answer of the mirrored, scaled or translated configuration, mapped back to
/// the base configuration's terms.
Answer unswap(Answer y) {
  y.normal = -y.normal;
  std::swap(y.wa, y.wb);
  return y;
}
Answer unscale(Answer y, Real s) {
  y.value /= s;
  y.error /= s;
  y.wa = y.wa / s;
  y.wb = y.wb / s;
  return y;
}
Answer untranslate(Answer y, const Vec3& offset) {
  y.wa -= offset;
  y.wb -= offset;
  return y;
}

std::string show(const Answer& r) {
  return r.status + (r.intersect ? " intersect" : " apart") + " value " + num(r.value) + " (claimed error " +
         num(r.error) + ")" +
         (r.has_vectors ? " normal " + num(r.normal) + " wa " + num(r.wa) + " wb " + num(r.wb) : "");
}

/// How far B must move along n (world) to separate: h_A(n) + h_B(-n), the
/// support function of A - B.
Real depth_along(const Config& c, const Vec3& n) { return support_value(c.a, c.pa, n) + support_value(c.b, c.pb, -n); }

/// Witness positions: no setting bounds them (GJK and EPA converge on the
/// value; the witnesses are weighted sums of support points, with weights
/// from a nearly flat simplex when the shapes nearly touch, and the polish
/// of curved pairs takes one support point), so they are held to the only
/// documented accuracy, the query format's: each witness within 1e-6 x size
/// of its shape (../shared/tools/check-pairs), on top of the value's error.
constexpr Real kFormatWitnessTol = 1e-6;
Real position_floor(Real size) { return kFormatWitnessTol * size; }

struct Counts {
  int pairs = 0, intersecting = 0, checks = 0, near_touching = 0;
};

/// x: the base answer (configuration c, near the origin); y: the other
/// answer, mapped back. `extra`: what the mapping itself may change (length).
void compare(const Answer& x, const Answer& y, const Config& c, bool unique, Real extra, const std::string& what,
             Counts& counts) {
  const QuerySettings st;
  const Real tol = x.error + y.error + extra;
  ++counts.checks;
  if (x.intersect != y.intersect) {
    // Flags may differ only between answers that are both touching to within the errors.
    EXPECT_LE(std::fmax(x.value, y.value), tol + st.touch_tol * c.size)
        << what << ": intersect flags differ\n  base:  " << show(x) << "\n  other: " << show(y);
    ++counts.near_touching;
    return;
  }
  EXPECT_LE(std::fabs(x.value - y.value), tol)
      << what << ": " << (x.intersect ? "depth" : "distance") << " differs by " << num(std::fabs(x.value - y.value))
      << "\n  base:  " << show(x) << "\n  other: " << show(y);
  if (!x.has_vectors || !y.has_vectors) return;
  // The mapping moves B relative to A by up to `extra`: the closest point of
  // A - B moves by up to 2 extra (projection is 1-Lipschitz), the normal by 2 extra / v.
  const Real v = std::fmin(x.value, y.value);
  const Real angle_tol =
      v > 2 * tol ? x.angle_error + y.angle_error + 2 * extra / v : 4;  // 4 rad: undefined near touching
  const Real angle = std::acos(std::clamp(dot(x.normal, y.normal), Real(-1), Real(1)));
  if (!x.intersect) {
    EXPECT_LE(angle, angle_tol) << what << ": separated normals " << num(angle) << " rad apart\n  base:  " << show(x)
                                << "\n  other: " << show(y);
  } else {
    // Each normal must achieve the other answer's depth: B moved by depth
    // along it separates the shapes (up to the errors).
    EXPECT_LE(depth_along(c, y.normal) - x.value, tol)
        << what << ": the other normal needs a longer move, " << num(depth_along(c, y.normal))
        << "\n  base:  " << show(x) << "\n  other: " << show(y);
    if (unique) {
      EXPECT_LE(angle, angle_tol) << what << ": normals " << num(angle) << " rad apart\n  base:  " << show(x)
                                  << "\n  other: " << show(y);
    }
  }
  if (unique) {
    // A normal off by angle_tol moves a support point by up to size x angle_tol.
    const Real wtol = c.size * angle_tol + tol + position_floor(c.size);
    EXPECT_LE(length(x.wa - y.wa), wtol) << what << ": witness_a moved by " << num(length(x.wa - y.wa))
                                         << "\n  base:  " << show(x) << "\n  other: " << show(y);
    EXPECT_LE(length(x.wb - y.wb), wtol) << what << ": witness_b moved by " << num(length(x.wb - y.wb))
                                         << "\n  base:  " << show(x) << "\n  other: " << show(y);
  }
}

/// A lower bound on the distance from world point w to the shape (<= 0
/// inside), from the shape's closed form, independent of GJK: the largest
/// signed distance to a supporting plane (cylinders, cones, polytopes), the
/// exact distance (points, segments, boxes, with margins), or the gauge
/// function g (g <= 1 inside) times a ball about the origin that the shape
/// holds, (g - 1) * inradius (ellipsoids, superellipsoids).
Real outside_by(const Shape& s, const Transform& pose, const Vec3& w) {
  const Vec3 p = apply_inverse(pose, w);
  const Real core = std::visit(
      [&](const auto& c) -> Real {
        using T = std::decay_t<decltype(c)>;
        if constexpr (std::is_same_v<T, Point>) {
          return length(p);
        } else if constexpr (std::is_same_v<T, Segment>) {
          const Vec3 t = c.b - c.a;
          const Real u = std::clamp(dot(p - c.a, t) / std::fmax(dot(t, t), Real(1e-300)), Real(0), Real(1));
          return length(p - (c.a + t * u));
        } else if constexpr (std::is_same_v<T, Box>) {
          const Vec3 e{std::fmax(std::fabs(p.x) - c.half_extents.x, Real(0)),
                       std::fmax(std::fabs(p.y) - c.half_extents.y, Real(0)),
                       std::fmax(std::fabs(p.z) - c.half_extents.z, Real(0))};
          return length(e);
        } else if constexpr (std::is_same_v<T, Cylinder>) {
          return std::fmax(std::hypot(p.x, p.y) - c.radius, std::fabs(p.z) - c.half_height);
        } else if constexpr (std::is_same_v<T, Cone>) {
          // The side is the line from the rim (r, -h) to the apex (0, h) in (rho, z).
          const Real side = ((std::hypot(p.x, p.y) - c.radius) * 2 * c.half_height + (p.z + c.half_height) * c.radius) /
                            std::hypot(2 * c.half_height, c.radius);
          return std::fmax(side, -c.half_height - p.z);
        } else if constexpr (std::is_same_v<T, Ellipsoid>) {
          const Real g = length(Vec3{p.x / c.radii.x, p.y / c.radii.y, p.z / c.radii.z});
          return (g - 1) * std::fmin(c.radii.x, std::fmin(c.radii.y, c.radii.z));
        } else if constexpr (std::is_same_v<T, Superellipsoid>) {
          // F is homogeneous of degree 2/e1, so g = F^(e1/2); the shape holds
          // the octahedron of vertices +-radii (its e = 2 limit).
          const Real xy =
              std::pow(std::pow(std::fabs(p.x / c.radii.x), 2 / c.e2) + std::pow(std::fabs(p.y / c.radii.y), 2 / c.e2),
                       c.e2 / c.e1);
          const Real g = std::pow(xy + std::pow(std::fabs(p.z / c.radii.z), 2 / c.e1), c.e1 / 2);
          const Vec3 inv{1 / c.radii.x, 1 / c.radii.y, 1 / c.radii.z};
          return (g - 1) / length(inv);
        } else if constexpr (std::is_same_v<T, Polytope>) {
          const PolytopeData& d = *c.data;
          Real best = -std::numeric_limits<Real>::infinity();
          for (std::size_t f = 0; f < d.facet_normals.size(); ++f)
            best = std::fmax(best, dot(d.facet_normals[f], p - d.vertices[d.facet_vertices[d.facet_begin[f]]]));
          return d.facet_normals.empty() ? 0 : best;
        } else {
          return 0;  // triangles: not used by the families
        }
      },
      s.core);
  return core - s.margin;
}

/// The answer's own contract (conventions.md) in configuration c, near the
/// origin: a unit normal; the value certified by the normal (moving B by
/// depth * normal separates the shapes just so; the plane normal to a
/// separated pair's normal parts them by the distance); witness_b -
/// witness_a = distance * normal, or witness_a - witness_b = depth * normal;
/// each witness lies in its shape, at its shape's extreme along the normal,
/// so that swapped witnesses mean something where they are not unique.
void check_contract(const Answer& r, const Config& c, const std::string& what) {
  if (!r.has_vectors) return;
  const Real reach = std::fmax(max_abs(c.pa.translation), max_abs(c.pb.translation));
  const Real tol = 2 * r.error + kRoundOff * (c.size + reach);
  const Real pos_tol = tol + position_floor(c.size);
  EXPECT_NEAR(length(r.normal), 1.0, 1e-12) << what << ": " << show(r);
  EXPECT_GE(r.value, 0) << what << ": a distance or depth below zero: " << show(r);
  // D(n) = h_A(n) + h_B(-n): the move along n that separates; -D(n): the
  // gap the plane normal to n leaves. The convergence criteria (GJK's
  // duality gap, EPA's support gap) bound |D(n) -+ value| by the claimed error.
  const Real certified = r.intersect ? depth_along(c, r.normal) : -depth_along(c, r.normal);
  EXPECT_LE(std::fabs(certified - r.value), tol)
      << what << ": along the reported normal the " << (r.intersect ? "separating move is " : "separating gap is ")
      << num(certified) << ", " << num(certified - r.value) << " off the value: " << show(r);
  const Vec3 gap = r.intersect ? r.wa - r.wb : r.wb - r.wa;
  const Real along = dot(gap, r.normal), across = length(gap - r.normal * along);
  EXPECT_LE(std::fabs(along - r.value), pos_tol)
      << what << ": |witness difference| " << num(along) << " is not the value: " << show(r);
  EXPECT_LE(across, r.value * r.angle_error + pos_tol)
      << what << ": witness difference " << num(across) << " across the normal: " << show(r);
  // In the shapes (outside_by is a lower bound on the distance, so it cannot
  // raise a false alarm), and not beyond their extremes along the normal.
  const Real out_a = outside_by(c.a, c.pa, r.wa), out_b = outside_by(c.b, c.pb, r.wb);
  EXPECT_LE(out_a, pos_tol) << what << ": witness_a at least " << num(out_a) << " outside A: " << show(r);
  EXPECT_LE(out_b, pos_tol) << what << ": witness_b at least " << num(out_b) << " outside B: " << show(r);
  const Real slack_a = support_value(c.a, c.pa, r.normal) - dot(r.normal, r.wa);
  const Real slack_b = support_value(c.b, c.pb, -r.normal) + dot(r.normal, r.wb);
  EXPECT_GE(std::fmin(slack_a, slack_b), -pos_tol)
      << what << ": a witness beyond its shape's extreme along the normal, by " << num(-std::fmin(slack_a, slack_b))
      << ": " << show(r);
}

std::string label(const Family& f, std::size_t i, const char* order, const std::string& variant) {
  return f.name + " #" + std::to_string(i) + " " + order + " " + variant + " [" + f.pairs[i].what + "]";
}

// ------------------------------------------------------------ properties

void check_swap(const Family& f) {
  Counts counts;
  for (std::size_t i = 0; i < f.pairs.size(); ++i) {
    const Pair& p = f.pairs[i];
    SCOPED_TRACE(f.name + " #" + std::to_string(i) + ": " + property::describe(p));
    const Config ab = make_config(p, false), ba = make_config(p, true);
    const Answer pen_ab = penetration_answer(ab), pen_ba = penetration_answer(ba);
    const Answer dist_ab = distance_answer(ab), dist_ba = distance_answer(ba);
    ++counts.pairs;
    counts.intersecting += pen_ab.intersect;
    check_contract(pen_ab, ab, label(f, i, "AB", "penetration"));
    check_contract(pen_ba, ba, label(f, i, "BA", "penetration"));
    check_contract(dist_ab, ab, label(f, i, "AB", "distance"));
    check_contract(dist_ba, ba, label(f, i, "BA", "distance"));
    compare(pen_ab, unswap(pen_ba), ab, p.unique, 0, label(f, i, "AB/BA", "penetration swapped"), counts);
    compare(dist_ab, unswap(dist_ba), ab, p.unique, 0, label(f, i, "AB/BA", "distance swapped"), counts);
    // The boolean test in both orders, against penetration's answer: they may
    // differ only where that answer is touching within its error.
    const QuerySettings st;
    const Real touching = pen_ab.error + st.touch_tol * ab.size;
    const bool hits[2] = {intersect(ab.a, ab.pa, ab.b, ab.pb), intersect(ba.a, ba.pa, ba.b, ba.pb)};
    for (int k = 0; k < 2; ++k) {
      ++counts.checks;
      if (hits[k] != pen_ab.intersect) {
        EXPECT_LE(pen_ab.value, touching)
            << label(f, i, k ? "BA" : "AB", "intersect()") << " says " << hits[k] << ", penetration: " << show(pen_ab);
      }
    }
  }
  ::testing::Test::RecordProperty("pairs", counts.pairs);
  ::testing::Test::RecordProperty("checks", counts.checks);
  std::printf("[ family   ] %s: %d pairs, %d intersecting, %d swap comparisons (%d near touching)\n", f.name.c_str(),
              counts.pairs, counts.intersecting, counts.checks, counts.near_touching);
  if (f.mixed) {  // the generator exercises both outcomes, or the test passes vacuously
    EXPECT_GE(counts.intersecting, counts.pairs / 5) << f.name;
    EXPECT_LE(counts.intersecting, counts.pairs * 4 / 5) << f.name;
  }
}

void check_scale(const Family& f) {
  Counts counts;
  for (std::size_t i = 0; i < f.pairs.size(); ++i) {
    const Pair& p = f.pairs[i];
    SCOPED_TRACE(f.name + " #" + std::to_string(i) + ": " + property::describe(p));
    for (const bool swapped : {false, true}) {
      const char* order = swapped ? "BA" : "AB";
      const Config base = make_config(p, swapped);
      const Answer pen = penetration_answer(base), dist = distance_answer(base);
      const bool hit = intersect(base.a, base.pa, base.b, base.pb);
      for (const Real s : kScales) {
        const Config c = make_config(p, swapped, s);
        const std::string variant = "scaled by " + num(s);
        const Answer pen_s = penetration_answer(c), dist_s = distance_answer(c);
        check_contract(pen_s, c, label(f, i, order, "penetration " + variant));
        check_contract(dist_s, c, label(f, i, order, "distance " + variant));
        // Scaling the shapes rounds each coordinate once: eps x size moves.
        const Real extra = 4 * kEps * base.size;
        compare(pen, unscale(pen_s, s), base, p.unique, extra, label(f, i, order, "penetration " + variant), counts);
        compare(dist, unscale(dist_s, s), base, p.unique, extra, label(f, i, order, "distance " + variant), counts);
        const bool hit_s = intersect(c.a, c.pa, c.b, c.pb);
        ++counts.checks;
        if (hit_s != hit) {
          const QuerySettings st;
          EXPECT_LE(pen.value, pen.error + st.touch_tol * base.size)
              << label(f, i, order, "intersect() " + variant) << " says " << hit_s << ", unscaled " << hit
              << "; penetration: " << show(pen);
        }
      }
    }
  }
  ::testing::Test::RecordProperty("checks", counts.checks);
  std::printf("[ family   ] %s: %zu pairs x 2 orders x %zu scales, %d comparisons\n", f.name.c_str(), f.pairs.size(),
              std::size(kScales), counts.checks);
}

void check_translation(const Family& f) {
  Counts counts;
  for (std::size_t i = 0; i < f.pairs.size(); ++i) {
    const Pair& p = f.pairs[i];
    SCOPED_TRACE(f.name + " #" + std::to_string(i) + ": " + property::describe(p));
    for (const bool swapped : {false, true}) {
      const char* order = swapped ? "BA" : "AB";
      const Config base = make_config(p, swapped), far = make_config(p, swapped, 1, kOffset);
      const Answer pen = penetration_answer(base), dist = distance_answer(base);
      const std::string variant = "translated by " + num(kOffset);
      compare(pen, untranslate(penetration_answer(far), kOffset), base, p.unique, kOffsetRoundOff,
              label(f, i, order, "penetration " + variant), counts);
      compare(dist, untranslate(distance_answer(far), kOffset), base, p.unique, kOffsetRoundOff,
              label(f, i, order, "distance " + variant), counts);
      const bool hit = intersect(base.a, base.pa, base.b, base.pb), hit_far = intersect(far.a, far.pa, far.b, far.pb);
      ++counts.checks;
      if (hit_far != hit) {
        const QuerySettings st;
        EXPECT_LE(pen.value, pen.error + kOffsetRoundOff + st.touch_tol * base.size)
            << label(f, i, order, "intersect() " + variant) << " says " << hit_far << ", at the origin " << hit
            << "; penetration: " << show(pen);
      }
    }
  }
  ::testing::Test::RecordProperty("checks", counts.checks);
  std::printf("[ family   ] %s: %zu pairs x 2 orders, %d comparisons\n", f.name.c_str(), f.pairs.size(), counts.checks);
}

// What these families found, and how it was fixed (reproduce any pair by
// family and index):
//  [gjk-worse] on no progress GJK kept the new simplex even when its point
//    was farther (a point 1e-12 off a cylinder came out 0.66 apart).
//  [polish-witness] a penetration's witnesses on a cylinder or cone side were
//    A's support point, anywhere on a generator line, up to 3.1 units outside B.
//  [gjk-stall] separated kinked maxima (a cone's apex against the other's
//    side, a box corner at a cylinder's rim): GJK ended on a sliver triangle
//    (two rim points a micron apart, a far apex) whose normal, from an edge
//    through the far vertex, was tilted by eps * size / (short edge), and
//    whose closest point, the vertices' weighted sum, came out farther than
//    its own edge: normals certified to 1e-11..1e-9 relative, claimed 1e-11.
//    The triangle's normal now comes from its two shortest edges and its
//    closest point is the origin's projection along it (simplex.hpp).
//  [gjk-touch] a point or corner 1e-9 .. 1e-12 x size off a cone's side or
//    rim: a segment's closest point carried eps * |w| along the segment (a
//    normal 3e-8 rad off along a flat generator), and a flat tetrahedron of
//    three rim points "enclosed" an origin 1e-12 x size outside (its volumes'
//    round-off outweighs the distance), so answers and flags changed with
//    the order and the scale. The segment's point is made perpendicular
//    again, and an enclosure is confirmed face by face with accurate normals.
//  Checks failing on 4df9089, when CurvedSizeRatios, NearTouchingCurved and
//  KinkedMaxima were disabled for swap and scale: 14, 48, 16, 129, 14 and 38
//  (the largest disagreement 4e-11 x size); all pass since these fixes.

TEST(PropertySwap, RandomPolytopes) { check_swap(property::random_polytopes()); }
TEST(PropertyScale, RandomPolytopes) { check_scale(property::random_polytopes()); }
TEST(PropertyTranslation, RandomPolytopes) { check_translation(property::random_polytopes()); }

TEST(PropertySwap, NearSphericalHulls) { check_swap(property::near_spherical_hulls()); }
TEST(PropertyScale, NearSphericalHulls) { check_scale(property::near_spherical_hulls()); }
TEST(PropertyTranslation, NearSphericalHulls) { check_translation(property::near_spherical_hulls()); }

TEST(PropertySwap, Boxes) { check_swap(property::boxes()); }
TEST(PropertyScale, Boxes) { check_scale(property::boxes()); }
TEST(PropertyTranslation, Boxes) { check_translation(property::boxes()); }

TEST(PropertySwap, ParallelFaces) { check_swap(property::parallel_faces()); }
TEST(PropertyScale, ParallelFaces) { check_scale(property::parallel_faces()); }
TEST(PropertyTranslation, ParallelFaces) { check_translation(property::parallel_faces()); }

TEST(PropertySwap, Spheres) { check_swap(property::spheres()); }
TEST(PropertyScale, Spheres) { check_scale(property::spheres()); }
TEST(PropertyTranslation, Spheres) { check_translation(property::spheres()); }

TEST(PropertySwap, Capsules) { check_swap(property::capsules()); }
TEST(PropertyScale, Capsules) { check_scale(property::capsules()); }
TEST(PropertyTranslation, Capsules) { check_translation(property::capsules()); }

TEST(PropertySwap, CurvedSizeRatios) { check_swap(property::curved_size_ratios()); }
TEST(PropertyScale, CurvedSizeRatios) { check_scale(property::curved_size_ratios()); }
TEST(PropertyTranslation, CurvedSizeRatios) { check_translation(property::curved_size_ratios()); }

TEST(PropertySwap, SunkIntoSide) { check_swap(property::sunk_into_side()); }
TEST(PropertyScale, SunkIntoSide) { check_scale(property::sunk_into_side()); }
TEST(PropertyTranslation, SunkIntoSide) { check_translation(property::sunk_into_side()); }

TEST(PropertySwap, NearTouchingCurved) { check_swap(property::near_touching_curved()); }
TEST(PropertyScale, NearTouchingCurved) { check_scale(property::near_touching_curved()); }
TEST(PropertyTranslation, NearTouchingCurved) { check_translation(property::near_touching_curved()); }

TEST(PropertySwap, KinkedMaxima) { check_swap(property::kinked_maxima()); }
TEST(PropertyScale, KinkedMaxima) { check_scale(property::kinked_maxima()); }
TEST(PropertyTranslation, KinkedMaxima) { check_translation(property::kinked_maxima()); }

// Curved cores with margins (rounded cylinders, cones, ellipsoids): the
// three queries agree on touching, and no distance comes out below zero
// (distance() once tested the margin before polishing a stalled answer,
// which can lower the core gap below the margins).
TEST(PropertyMargins, CurvedCoresWithMarginsAgreeAcrossQueries) {
  int pairs = 0;
  for (Family f : {property::curved_size_ratios(), property::near_touching_curved()}) {
    for (std::size_t i = 0; i < f.pairs.size(); ++i) {
      Pair p = f.pairs[i];
      // A margin of 1% of each core's size, and B moved out by both margins:
      // the rounded pair is as near touching as the cores were.
      p.a.margin = 0.01 * bounding_radius(p.a);
      p.b.margin = 0.01 * bounding_radius(p.b);
      const Real size = 2 * std::fmax(bounding_radius(p.a), bounding_radius(p.b));
      const Vec3 away = p.tb - p.ta;
      if (length(away) > 0) p.tb += normalized(away) * (p.a.margin + p.b.margin);
      for (const bool swapped : {false, true}) {
        const Shape& a = swapped ? p.b : p.a;
        const Shape& b = swapped ? p.a : p.b;
        const Transform ta = swapped ? p.pose_b() : p.pose_a(), tb = swapped ? p.pose_a() : p.pose_b();
        const DistanceResult d = distance(a, ta, b, tb);
        const PenetrationResult r = penetration(a, ta, b, tb);
        const std::string what = f.name + " #" + std::to_string(i) + (swapped ? " BA" : " AB");
        EXPECT_GE(d.distance, 0) << what;
        EXPECT_GE(r.distance, 0) << what;
        EXPECT_GE(r.depth, 0) << what;
        // Flags may differ only within the touch tolerance of contact.
        if (d.intersect != r.intersect) {
          EXPECT_LE(std::fmax(d.distance, r.depth), 1e-9 * size) << what << ": intersect flags differ";
        } else if (!d.intersect) {
          EXPECT_NEAR(d.distance, r.distance, 1e-9 * size) << what;
        }
        ++pairs;
      }
    }
  }
  EXPECT_GT(pairs, 100);
}

TEST(PropertySwap, Containment) { check_swap(property::containment()); }
TEST(PropertyScale, Containment) { check_scale(property::containment()); }
TEST(PropertyTranslation, Containment) { check_translation(property::containment()); }

// The boolean test starts cold from the shapes' origins, or warm from the
// search directions of GJK's last simplex (a cache): on every family, in
// both orders, both give penetration()'s answer, except within the touch
// tolerance. (A cold start by Minkowski portal refinement was tried here:
// 5-7% faster on deep overlaps of distinct shapes, none on the generated
// pairs, and not kept; docs/benchmarks.md.)
TEST(PropertyBoolean, ColdAndWarmCallsGivePenetrationsAnswer) {
  int pairs = 0, intersecting = 0;
  const QuerySettings st;
  for (const Family& f : {property::random_polytopes(), property::near_spherical_hulls(), property::boxes(),
                          property::parallel_faces(), property::spheres(), property::capsules(),
                          property::curved_size_ratios(), property::sunk_into_side(), property::near_touching_curved(),
                          property::kinked_maxima(), property::containment()}) {
    for (std::size_t i = 0; i < f.pairs.size(); ++i) {
      for (const bool swapped : {false, true}) {
        const Config c = make_config(f.pairs[i], swapped);
        const std::string what = label(f, i, swapped ? "BA" : "AB", "intersect()");
        const Answer pen = penetration_answer(c);
        GjkCache cache;
        const bool cold = intersect(c.a, c.pa, c.b, c.pb);
        distance(c.a, c.pa, c.b, c.pb, &cache);  // fills the cache: the next call replays it
        ASSERT_GT(cache.size, 0) << what;
        const bool warm = intersect(c.a, c.pa, c.b, c.pb, &cache);
        const Real touching = pen.error + st.touch_tol * c.size;
        if (cold != pen.intersect) {
          EXPECT_LE(pen.value, touching) << what << " cold says " << cold << ": " << show(pen);
        }
        if (warm != pen.intersect) {
          EXPECT_LE(pen.value, touching) << what << " warm says " << warm << ": " << show(pen);
        }
        ++pairs;
        intersecting += pen.intersect;
      }
    }
  }
  EXPECT_GT(intersecting, pairs / 5);
  EXPECT_LT(intersecting, pairs * 4 / 5);
}

}  // namespace
}  // namespace gjkdem
