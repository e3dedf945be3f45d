// The exact signs (shape/predicates.hpp) where the floating-point filter
// cannot answer: products of tiny differences that underflow to zero must
// still give the true sign, and coincident points zero.
#include <gtest/gtest.h>

#include "gjkdem/shape/predicates.hpp"

namespace gjkdem {
namespace {

TEST(Predicates, TinyCoordinatesKeepTheirSigns) {
  // Products of three 1e-200 differences (1e-600) underflow to zero: the
  // filter's permanent is 0, yet the tetrahedron has a volume.
  const Real e = 1e-200;
  const Vec3 o{0, 0, 0}, x{e, 0, 0}, y{0, e, 0}, z{0, 0, e};
  EXPECT_EQ(orient3d(o, x, y, z), 1);
  EXPECT_EQ(orient3d(o, y, x, z), -1);
  // Products of two 1e-170 differences (1e-340) underflow too.
  const Real f = 1e-170;
  EXPECT_EQ(cross_sign(o, {f, 0, 0}, o, {0, f, 0}, 2), 1);
  EXPECT_EQ(cross_sign(o, {0, f, 0}, o, {f, 0, 0}, 2), -1);
  // Scaled to 1 the same signs.
  EXPECT_EQ(orient3d(o, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}), 1);
}

TEST(Predicates, CoincidentAndCollinearPointsAreZero) {
  const Vec3 o{0, 0, 0}, x{1e-200, 0, 0}, y{0, 1e-200, 0};
  EXPECT_EQ(orient3d(o, x, y, o), 0);  // a repeated point
  EXPECT_EQ(orient3d(o, x, x, y), 0);
  EXPECT_EQ(orient3d(o, x, {2e-200, 0, 0}, y), 0);  // three on a line
  EXPECT_EQ(cross_sign(o, x, o, {3e-200, 0, 0}, 2), 0);  // parallel
  EXPECT_EQ(cross_sign(o, x, o, o, 2), 0);
}

}  // namespace
}  // namespace gjkdem
