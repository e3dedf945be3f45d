#pragma once
// Exact signs of the determinants that decide topology on triangle surfaces
// (which side of a plane a point lies on, whether an edge passes through a
// triangle). Inputs are doubles taken as exact; each sign is right for every
// input: a floating-point filter answers when its error bound allows and
// exact rational arithmetic (GMP) otherwise.
//
// Surface contact (surface_overlap.hpp) decides against a symbolically
// perturbed pair: surface B moved by delta = (e, e^2, e^3), e -> 0+. Every
// decision then has a sign (no point lies on a face, no edge crosses an
// edge), the same decision is taken the same way wherever it is asked, and
// the quantities that are continuous in B's position (volume, centroid) are
// those of the unmoved pair.
#include "gjkdem/math/vec3.hpp"

namespace gjkdem {

/// Sign (-1, 0, 1) of det[b - a, c - a, d - a]: positive when d lies on the
/// side of the plane abc that (b - a) x (c - a) points to.
int orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

/// Sign of component `axis` of (q - p) x (s - r).
int cross_sign(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s, int axis);

/// Sign of (b - a) x (c - a) . e_axis: the orientation of triangle abc seen
/// down `axis` (its projection on the other two coordinates, ccw positive).
inline int orient2d(const Vec3& a, const Vec3& b, const Vec3& c, int axis) { return cross_sign(a, b, a, c, axis); }

/// Which of the two surfaces a point or a triangle comes from: B is the one
/// symbolically moved by delta.
enum class Side : unsigned char { A, B };

/// orient3d(a, b, c, d) with the points of surface B moved by delta: `abc`
/// says which surface the triangle comes from; d comes from the other one.
/// Never 0 for a triangle with area.
int perturbed_orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, Side abc);
/// The same, and whether d lies on the plane abc exactly (before the move).
int perturbed_orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, Side abc, bool& on_plane);

/// perturbed_orient3d of three points d[k] against one triangle abc: the
/// same signs and on-plane flags, with the triangle's normal and the filter's
/// bounds made once (a surface overlap asks this for every pair of
/// triangles whose boxes meet).
void perturbed_orient3d_three(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3 (&d)[3], Side abc, int (&sign)[3],
                              bool (&on_plane)[3]);

/// orient3d(p, q, r, s) with edge pq from one surface and edge rs from the
/// other (`pq` says which), B's moved by delta. 0 only when the two edges
/// are parallel (they then never decide a crossing).
int perturbed_orient3d_edges(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s, Side pq);

}  // namespace gjkdem
