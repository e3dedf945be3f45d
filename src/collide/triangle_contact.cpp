#include "gjkdem/collide/triangle_contact.hpp"

#include "gjkdem/collide/query.hpp"

namespace gjkdem {

TriangleContact triangle_contact(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, const Vec3& e,
                                 const Vec3& f, Real rho, Real tol) noexcept {
  // Local frames at the centroids keep round-off proportional to the triangles'
  // size even far from the origin.
  const Vec3 ca = (a + b + c) / 3, cd = (d + e + f) / 3;
  const Shape abc{Triangle{{a - ca, b - ca, c - ca}}}, def{Triangle{{d - cd, e - cd, f - cd}}};
  QuerySettings st;
  st.gjk_rel_tol = tol;
  const DistanceResult r = distance(abc, Transform::from(ca, {}), def, Transform::from(cd, {}), nullptr, st);
  TriangleContact out;
  out.status = r.status;
  out.iterations = r.iterations;
  out.distance = r.intersect ? 0 : r.distance;
  out.contact = r.intersect || r.distance <= rho;
  out.witness_a = r.witness_a;
  out.witness_b = r.witness_b;
  out.normal = r.normal;
  return out;
}

}  // namespace gjkdem
