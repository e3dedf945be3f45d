#include "gjkdem/shape/aabb.hpp"

namespace gjkdem {

Aabb aabb(const Shape& shape, const Transform& pose, Real pad) noexcept {
  // A hull small enough to be scanned (no vertex graph), without a margin:
  // its corners placed once, fewer products than six scans of them. The
  // same bits: the scan along R^T e_k ranks the corners by the products
  // that e_k . (R v) is made of, and adding the translation keeps the order.
  if (const auto* p = std::get_if<Polytope>(&shape.core); p && p->data->adj.empty() && shape.margin == 0) {
    const PolytopeData& d = *p->data;
    Vec3 lo = apply(pose, d.vertices[0]), hi = lo;
    for (std::size_t i = 1; i < d.vertices.size(); ++i) {
      const Vec3 w = apply(pose, d.vertices[i]);
      for (int k = 0; k < 3; ++k) {
        lo[k] = w[k] < lo[k] ? w[k] : lo[k];  // not fmin: a call into libm
        hi[k] = w[k] > hi[k] ? w[k] : hi[k];
      }
    }
    const Vec3 grow{pad, pad, pad};
    return {lo - grow, hi + grow};
  }
  Aabb box;
  for (int k = 0; k < 3; ++k) {
    Vec3 axis;
    axis[k] = 1;
    // Support along +-axis in world = pose applied to the support along R^T axis.
    const Vec3 local = apply_inverse_rotation(pose, axis);
    box.hi[k] = apply(pose, support(shape, local))[k] + pad;
    box.lo[k] = apply(pose, support(shape, -local))[k] - pad;
  }
  return box;
}

}  // namespace gjkdem
