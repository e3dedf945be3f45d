#include "gjkdem/shape/aabb.hpp"

namespace gjkdem {

Aabb aabb(const Shape& shape, const Transform& pose, Real pad) noexcept {
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
