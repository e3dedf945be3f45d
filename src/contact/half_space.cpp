#include "gjkdem/contact/half_space.hpp"

#include <array>
#include <cmath>
#include <vector>

#include "gjkdem/math/vec2.hpp"
#include "gjkdem/shape/convex_hull.hpp"
#include "gjkdem/tolerances.hpp"

namespace gjkdem {
namespace {


// The surface of a polytope or box core as world-frame triangles, outward.
bool surface_triangles(const Shape& s, const Transform& pose, std::vector<std::array<Vec3, 3>>& out) {
  out.clear();
  if (s.margin > 0) return false;
  if (const auto* p = std::get_if<Polytope>(&s.core)) {
    const PolytopeData& d = *p->data;
    if (d.triangles.empty()) return false;
    for (const auto& t : d.triangles)
      out.push_back({apply(pose, d.vertices[t[0]]), apply(pose, d.vertices[t[1]]), apply(pose, d.vertices[t[2]])});
    return true;
  }
  if (const auto* b = std::get_if<Box>(&s.core)) {
    const Vec3 h = b->half_extents;
    auto corner = [&](int i) {
      return apply(pose, Vec3{(i & 1) ? h.x : -h.x, (i & 2) ? h.y : -h.y, (i & 4) ? h.z : -h.z});
    };
    // Faces as corner-index quads, counter-clockwise seen from outside.
    static constexpr int kQuads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                         {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    for (const auto& q : kQuads) {
      out.push_back({corner(q[0]), corner(q[1]), corner(q[2])});
      out.push_back({corner(q[0]), corner(q[2]), corner(q[3])});
    }
    return true;
  }
  return false;
}

// Volume below the plane and the cut face, by clipping each surface triangle.
// The volume is summed as tetrahedra on a reference point of the plane, so the
// cut face itself (which lies in the plane) adds nothing.
void clip_below(const std::vector<std::array<Vec3, 3>>& tris, const Vec3& point, const Vec3& n, Real scale,
                HalfSpaceContact& c) {
  const Vec3 ref = c.deepest + n * (c.depth);  // on the plane, next to the body
  const Real on_plane = kHullRelTol * scale;
  std::vector<Vec3> cut;  // points of the cut face
  Real six_volume = 0;
  Vec3 weighted_centre;  // sum of six times a tetrahedron's volume times four times its centroid
  for (const auto& t : tris) {
    Real s[3];
    for (int k = 0; k < 3; ++k) s[k] = dot(n, t[k] - point);
    Vec3 poly[4];
    int m = 0;
    for (int k = 0; k < 3; ++k) {
      const int l = (k + 1) % 3;
      if (s[k] <= 0) poly[m++] = t[k];
      if (std::fabs(s[k]) <= on_plane) cut.push_back(t[k]);
      if ((s[k] < 0 && s[l] > 0) || (s[k] > 0 && s[l] < 0)) {
        const Vec3 x = t[k] + (t[l] - t[k]) * (s[k] / (s[k] - s[l]));
        poly[m++] = x;
        cut.push_back(x);
      }
    }
    for (int k = 1; k + 1 < m; ++k) {
      const Real v6 = dot(poly[0] - ref, cross(poly[k] - ref, poly[k + 1] - ref));
      six_volume += v6;
      weighted_centre += (poly[0] + poly[k] + poly[k + 1] - ref * 3) * v6;
    }
  }
  c.volume = std::fmax(six_volume / 6, Real(0));
  c.has_volume = true;
  c.centroid = six_volume > 0 ? ref + weighted_centre / (4 * six_volume) : c.deepest;
  c.depth_integral = c.volume * std::fmax(-dot(n, c.centroid - point), Real(0));
  c.face_centroid = c.deepest + n * c.depth;
  if (cut.size() < 3) return;
  Vec3 t1, t2;
  orthonormal_basis(n, t1, t2);
  std::vector<Vec2> flat(cut.size());
  for (std::size_t k = 0; k < cut.size(); ++k) flat[k] = {dot(cut[k] - ref, t1), dot(cut[k] - ref, t2)};
  const std::vector<int> hull = convex_hull_2d(flat, on_plane);
  if (hull.size() < 3) return;
  Real twice_area = 0;
  Vec2 weighted{0, 0};
  for (std::size_t k = 1; k + 1 < hull.size(); ++k) {
    const Vec2 a = flat[hull[0]], b = flat[hull[k]], d = flat[hull[k + 1]];
    const Real w = cross(b - a, d - a);
    twice_area += w;
    weighted = weighted + (a + b + d) * (w / 3);
  }
  if (!(twice_area > 0)) return;
  c.area = twice_area / 2;
  const Vec2 centre = weighted * (1 / twice_area);
  c.face_centroid = ref + t1 * centre.x + t2 * centre.y;
}

}  // namespace

HalfSpaceContact half_space_contact(const Shape& shape, const Transform& pose, const Vec3& point,
                                    const Vec3& normal) {
  HalfSpaceContact c;
  c.deepest = apply(pose, support(shape, apply_inverse_rotation(pose, -normal)));
  c.depth = -dot(normal, c.deepest - point);
  c.touching = c.depth >= 0;
  if (!c.touching) return c;
  if (std::holds_alternative<Point>(shape.core)) {  // sphere: a spherical cap
    const Real r = shape.margin, h = std::fmin(c.depth, 2 * r);
    const Vec3 centre = apply(pose, Vec3{});
    const Real d = dot(normal, centre - point);  // centre's height above the plane
    c.has_volume = true;
    c.volume = kPi * h * h * (3 * r - h) / 3;
    c.area = std::fmax(kPi * (r * r - d * d), Real(0));
    c.face_centroid = centre - normal * d;
    // The cap's centroid lies 3 (2r - h)^2 / (4 (3r - h)) from the centre.
    const Real from_centre = 3 * (2 * r - h) * (2 * r - h) / (4 * (3 * r - h));
    c.centroid = centre - normal * from_centre;
    c.depth_integral = c.volume * std::fmax(from_centre - d, Real(0));
    return c;
  }
  thread_local std::vector<std::array<Vec3, 3>> tris;
  if (surface_triangles(shape, pose, tris)) clip_below(tris, point, normal, bounding_radius(shape), c);
  return c;
}

}  // namespace gjkdem
