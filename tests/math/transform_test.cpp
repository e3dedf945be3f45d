#include "gjkdem/math/transform.hpp"

#include <gtest/gtest.h>

namespace gjkdem {
namespace {

TEST(Transform, RelativeComposesWithApply) {
  const Transform a = Transform::from({1, -2, 3}, normalized(Quat{0.3, -0.2, 0.5, 0.1}));
  const Transform b = Transform::from({-4, 5, 0.5}, normalized(Quat{-0.7, 0.1, 0.2, 0.6}));
  const Transform rel = relative(a, b);
  const Vec3 p{0.3, 0.7, -1.1};
  const Vec3 direct = apply(b, p);
  const Vec3 through = apply(a, apply(rel, p));
  EXPECT_NEAR(length(direct - through), 0.0, 1e-14);
  EXPECT_NEAR(length(apply_inverse(a, apply(a, p)) - p), 0.0, 1e-14);
}

TEST(Transform, QuaternionMatrixIsARotation) {
  const Quat q = normalized(Quat{0.2, 0.9, -0.3, 0.4});
  const Mat3 r = to_matrix(q);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(dot(r.row[i], r.row[j]), i == j ? 1.0 : 0.0, 1e-15);
  EXPECT_NEAR(dot(cross(r.row[0], r.row[1]), r.row[2]), 1.0, 1e-15);
  // 90 degrees about z maps x to y.
  const Vec3 y = rotate(quat_from_axis_angle({0, 0, 1}, std::acos(-1.0) / 2), {1, 0, 0});
  EXPECT_NEAR(y.y, 1.0, 1e-15);
}

TEST(Transform, OrthonormalBasisIsOrthonormal) {
  for (const Vec3 n : {Vec3{0, 0, 1}, Vec3{0, 0, -1}, normalized(Vec3{1, 2, 3}), normalized(Vec3{-1e-9, 1, 0})}) {
    Vec3 t1, t2;
    orthonormal_basis(n, t1, t2);
    EXPECT_NEAR(dot(t1, n), 0.0, 1e-15);
    EXPECT_NEAR(dot(t2, n), 0.0, 1e-15);
    EXPECT_NEAR(dot(t1, t2), 0.0, 1e-15);
    EXPECT_NEAR(length(t1), 1.0, 1e-15);
  }
}

}  // namespace
}  // namespace gjkdem
