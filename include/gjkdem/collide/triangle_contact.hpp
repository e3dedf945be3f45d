#pragma once
// The seed text's triangle-pair query GJK(A, B, C, D, E, F, rho, tol): are the
// triangles ABC and DEF closer than the margin rho? Wall meshes and
// non-convex particles are handled triangle by triangle with it.
#include "gjkdem/collide/status.hpp"
#include "gjkdem/math/vec3.hpp"
#include "gjkdem/tolerances.hpp"

namespace gjkdem {

struct TriangleContact {
  bool contact = false;  ///< distance <= rho (touching or overlapping counts)
  Real distance = 0;     ///< >= 0; 0 when the triangles intersect
  Vec3 witness_a;        ///< closest point on ABC (unset when they intersect)
  Vec3 witness_b;        ///< closest point on DEF
  Vec3 normal;           ///< unit, ABC -> DEF; zero when they intersect
  GjkStatus status = GjkStatus::Separated;
  int iterations = 0;
};

/// `rho` >= 0 is the contact margin (same unit as the points); `tol` the
/// relative GJK tolerance (see kGjkRelTol).
TriangleContact triangle_contact(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, const Vec3& e,
                                 const Vec3& f, Real rho, Real tol = kGjkRelTol) noexcept;

}  // namespace gjkdem
