// Issue 12's properties for the overlap region (contact/overlap.hpp), on the
// pair families of tests/collide/property_families.hpp: the volume is the
// same in both argument orders (centroid the same, contact normal negated),
// scales as s^3 (centroid as s) under a uniform scale from 1e-4 to 1e4, does
// not change under a common translation by (1e6, -1e6, 1e6), and never
// exceeds either body's volume.
//
// Tolerances, from tolerances.hpp:
//  - clipping counts a vertex within kOverlapRelTol x size of a plane as on
//    it, which moves the overlap's surface by at most that: the volume by at
//    most (its surface area) x kOverlapRelTol x size, and a convex body inside
//    a ball of diameter `size` has an area below pi size^2;
//  - the volume is a sum of one triple product per surface triangle, each
//    good to a few ulps of size^3: 64 eps size^3 per face (polygon) allowed;
//  - a common translation T rounds each pose's translation (see
//    kOffsetRoundOff in property_test.cpp): B moves relative to A by up to
//    2e-10, which changes the volume by at most |S_A| x that <= pi size^2 x it;
//  - the contact normal is held to the query format's 1e-4 rad
//    (../shared/tools/check-pairs), the only accuracy documented for it.
#include "gjkdem/contact/overlap.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "collide/property_families.hpp"
#include "gjkdem/shape/mass_properties.hpp"
#include "gjkdem/tolerances.hpp"

namespace gjkdem {
namespace {

using property::Family;
using property::num;
using property::Pair;

constexpr Real kEps = std::numeric_limits<Real>::epsilon();
constexpr Real kFormatAngle = 1e-4;
const Real kScales[] = {1e-4, 1e-2, 1e2, 1e4};
const Vec3 kOffset{1e6, -1e6, 1e6};
const Real kOffsetRoundOff = 4 * (std::nextafter(1e6, 2e6) - 1e6);

struct Config {
  Shape a, b;
  Transform pa, pb;
  Real size = 0;
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

struct Volume {
  OverlapResult r;
  Real tol = 0;  ///< what clipping and summation may change of r.volume
};

Volume overlap_of(const Config& c) {
  OverlapWorkspace work;
  Volume v;
  v.r = overlap(c.a, c.pa, c.b, c.pb, work);
  const Real s3 = c.size * c.size * c.size;
  v.tol = kPi * kOverlapRelTol * s3 + 64 * kEps * s3 * std::max(v.r.faces, 1);
  return v;
}

const char* name(OverlapStatus s) {
  switch (s) {
    case OverlapStatus::Empty: return "Empty";
    case OverlapStatus::Overlapping: return "Overlapping";
    default: return "Unsupported";
  }
}

std::string show(const Volume& v) {
  return std::string(name(v.r.status)) + " volume " + num(v.r.volume) + " (tol " + num(v.tol) + ") centroid " +
         num(v.r.centroid) + (v.r.has_normal ? " normal " + num(v.r.contact_normal) : " no normal") + ", " +
         std::to_string(v.r.faces) + " faces";
}

/// Volume of a shape when mass_properties has a closed form for it (not for
/// margins on cores other than points and segments).
bool body_volume(const Shape& s, Real& volume) {
  try {
    volume = mass_properties(s).volume;
    return true;
  } catch (const std::invalid_argument&) { return false; }
}

struct Counts {
  int pairs = 0, overlapping = 0, unsupported = 0, checks = 0;
};

/// x: the base answer; y: the other, mapped back (volume / s^3, centroid /
/// s or - T, normal negated for the swap). `extra_volume`, `extra_length`:
/// what the mapping itself may change.
void compare(const Volume& x, const Volume& y, Real size, Real extra_volume, Real extra_length, const std::string& what,
             Counts& counts) {
  ++counts.checks;
  const bool unsupported_x = x.r.status == OverlapStatus::Unsupported,
             unsupported_y = y.r.status == OverlapStatus::Unsupported;
  EXPECT_EQ(unsupported_x, unsupported_y)
      << what << ": supported in one only\n  base:  " << show(x) << "\n  other: " << show(y);
  if (unsupported_x || unsupported_y) return;
  const Real tol = x.tol + y.tol + extra_volume;
  EXPECT_LE(std::fabs(x.r.volume - y.r.volume), tol)
      << what << ": volumes differ by " << num(std::fabs(x.r.volume - y.r.volume)) << "\n  base:  " << show(x)
      << "\n  other: " << show(y);
  const Real v = std::fmin(x.r.volume, y.r.volume);
  if (x.r.status == OverlapStatus::Overlapping && y.r.status == OverlapStatus::Overlapping && v > 1e3 * tol) {
    // The centroid is the first moment over the volume: a moment error of
    // tol x size over a volume v moves it by tol x size / v.
    const Real ctol = 2 * tol * size / v + extra_length + 64 * kEps * size;
    EXPECT_LE(length(x.r.centroid - y.r.centroid), ctol)
        << what << ": centroids " << num(length(x.r.centroid - y.r.centroid)) << " apart\n  base:  " << show(x)
        << "\n  other: " << show(y);
    if (x.r.has_normal && y.r.has_normal) {
      const Real angle = std::acos(std::clamp(dot(x.r.contact_normal, y.r.contact_normal), Real(-1), Real(1)));
      EXPECT_LE(angle, kFormatAngle) << what << ": contact normals " << num(angle) << " rad apart\n  base:  " << show(x)
                                     << "\n  other: " << show(y);
    }
  }
}

/// 0 <= V <= min(vol A, vol B) + tol.
void check_bounds(const Volume& x, const Config& c, const std::string& what) {
  if (x.r.status == OverlapStatus::Unsupported) return;
  EXPECT_GE(x.r.volume, 0.0) << what << ": " << show(x);
  Real va = 0, vb = 0;
  if (body_volume(c.a, va)) {
    EXPECT_LE(x.r.volume, va + x.tol) << what << ": above A's volume " << num(va) << ": " << show(x);
  }
  if (body_volume(c.b, vb)) {
    EXPECT_LE(x.r.volume, vb + x.tol) << what << ": above B's volume " << num(vb) << ": " << show(x);
  }
}

Volume mirrored(Volume y) {
  y.r.contact_normal = -y.r.contact_normal;
  return y;
}
Volume unscaled(Volume y, Real s) {
  y.r.volume /= s * s * s;
  y.tol /= s * s * s;
  y.r.centroid = y.r.centroid / s;
  return y;
}
Volume untranslated(Volume y, const Vec3& offset) {
  y.r.centroid -= offset;
  return y;
}

std::string label(const Family& f, std::size_t i, const char* order, const std::string& variant) {
  return f.name + " #" + std::to_string(i) + " " + order + " " + variant + " [" + f.pairs[i].what + "]";
}

void check_swap(const Family& f) {
  Counts counts;
  for (std::size_t i = 0; i < f.pairs.size(); ++i) {
    const Pair& p = f.pairs[i];
    SCOPED_TRACE(f.name + " #" + std::to_string(i) + ": " + property::describe(p));
    const Config ab = make_config(p, false), ba = make_config(p, true);
    const Volume x = overlap_of(ab), y = overlap_of(ba);
    ++counts.pairs;
    counts.overlapping += x.r.status == OverlapStatus::Overlapping;
    counts.unsupported += x.r.status == OverlapStatus::Unsupported;
    check_bounds(x, ab, label(f, i, "AB", "overlap"));
    check_bounds(y, ba, label(f, i, "BA", "overlap"));
    compare(x, mirrored(y), ab.size, 0, 0, label(f, i, "AB/BA", "overlap swapped"), counts);
  }
  std::printf("[ family   ] %s: %d pairs, %d overlapping, %d unsupported\n", f.name.c_str(), counts.pairs,
              counts.overlapping, counts.unsupported);
  EXPECT_GT(counts.overlapping, counts.pairs / 5) << f.name << ": too few overlaps to test anything";
}

void check_scale(const Family& f) {
  Counts counts;
  for (std::size_t i = 0; i < f.pairs.size(); ++i) {
    const Pair& p = f.pairs[i];
    SCOPED_TRACE(f.name + " #" + std::to_string(i) + ": " + property::describe(p));
    for (const bool swapped : {false, true}) {
      const Config base = make_config(p, swapped);
      const Volume x = overlap_of(base);
      for (const Real s : kScales) {
        const Config c = make_config(p, swapped, s);
        const Volume y = overlap_of(c);
        const std::string variant = "overlap scaled by " + num(s);
        check_bounds(y, c, label(f, i, swapped ? "BA" : "AB", variant));
        // Scaling rounds each coordinate once: eps x size moves of the surface.
        const Real s3 = base.size * base.size * base.size;
        compare(x, unscaled(y, s), base.size, 4 * kPi * kEps * s3, 4 * kEps * base.size,
                label(f, i, swapped ? "BA" : "AB", variant), counts);
      }
    }
  }
  std::printf("[ family   ] %s: %d overlap comparisons\n", f.name.c_str(), counts.checks);
}

void check_translation(const Family& f) {
  Counts counts;
  for (std::size_t i = 0; i < f.pairs.size(); ++i) {
    const Pair& p = f.pairs[i];
    SCOPED_TRACE(f.name + " #" + std::to_string(i) + ": " + property::describe(p));
    for (const bool swapped : {false, true}) {
      const Config base = make_config(p, swapped), far = make_config(p, swapped, 1, kOffset);
      const Real area = kPi * base.size * base.size;
      compare(overlap_of(base), untranslated(overlap_of(far), kOffset), base.size, area * kOffsetRoundOff,
              kOffsetRoundOff, label(f, i, swapped ? "BA" : "AB", "overlap translated by " + num(kOffset)), counts);
    }
  }
  std::printf("[ family   ] %s: %d overlap comparisons\n", f.name.c_str(), counts.checks);
}

#define GJKDEM_OVERLAP_PROPERTY_TESTS(Name, family)           \
  TEST(PropertyOverlapSwap, Name) { check_swap(family()); }   \
  TEST(PropertyOverlapScale, Name) { check_scale(family()); } \
  TEST(PropertyOverlapTranslation, Name) { check_translation(family()); }

GJKDEM_OVERLAP_PROPERTY_TESTS(RandomPolytopes, property::random_polytopes)
GJKDEM_OVERLAP_PROPERTY_TESTS(NearSphericalHulls, property::near_spherical_hulls)
GJKDEM_OVERLAP_PROPERTY_TESTS(Boxes, property::boxes)
GJKDEM_OVERLAP_PROPERTY_TESTS(ParallelFaces, property::parallel_faces)
GJKDEM_OVERLAP_PROPERTY_TESTS(Spheres, property::spheres)
GJKDEM_OVERLAP_PROPERTY_TESTS(Containment, property::containment)

}  // namespace
}  // namespace gjkdem
