// The one contact dispatch (body.hpp): each kind of template part gets its
// PartKind, and every two kinds one ContactRoute, the same in either order.
#include <gtest/gtest.h>

#include <memory>

#include "gjkdem/dem/body.hpp"

namespace gjkdem::dem {
namespace {

using K = PartKind;
using R = ContactRoute;

TEST(PartKind, EachTemplatePartHasItsKind) {
  EXPECT_EQ(part_kind(make_template(Shape{Box{{0.1, 0.2, 0.3}}}), 0), K::Convex);
  const auto cube = std::make_shared<const Surface>(box_surface(Box{{0.1, 0.1, 0.1}}));
  EXPECT_EQ(part_kind(make_surface_template(cube, false), 0), K::Surface);
  const auto shell = std::make_shared<const Shell>(
      make_shell({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}, 0.01));
  EXPECT_EQ(part_kind(make_shell_template(shell, false), 0), K::Shell);
  // A compound: a convex part, then a surface part.
  const PlacedShape box{Shape{Box{{0.1, 0.1, 0.1}}}, Transform::from({-0.3, 0, 0}, Quat{})};
  const PlacedSurface ring{cube, Transform::from({0.3, 0, 0}, Quat{})};
  const ShapeTemplate compound = make_compound_template({&box, 1}, false, {&ring, 1});
  ASSERT_EQ(compound.parts.size(), 2u);
  EXPECT_EQ(part_kind(compound, 0), K::Convex);
  EXPECT_EQ(part_kind(compound, 1), K::Surface);
  // A mesh wall's piece: a WallPiece with a margin (the penetration laws),
  // a convex slab without (the volume law).
  const Triangle face{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}};
  ShapeTemplate piece = make_wall_template(Shape{face, 0.01});
  piece.wall_face = face;
  EXPECT_EQ(part_kind(piece, 0), K::WallPiece);
  EXPECT_NE(margin_piece(piece), nullptr);
  piece.shape.margin = 0;
  EXPECT_EQ(part_kind(piece, 0), K::Convex);
}

TEST(PartKind, EveryTwoKindsMeetByOneRouteInEitherOrder) {
  const K kinds[] = {K::Convex, K::Surface, K::Shell, K::WallPiece};
  // Rows and columns in the order of `kinds`, written out by hand.
  const R expected[4][4] = {
      {R::Convex, R::Patches, R::Shell, R::Convex},
      {R::Patches, R::Patches, R::Shell, R::Margin},
      {R::Shell, R::Shell, R::Shell, R::Margin},
      {R::Convex, R::Margin, R::Margin, R::Convex},
  };
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      EXPECT_EQ(pair_route(kinds[i], kinds[j]), expected[i][j]) << i << ", " << j;
      EXPECT_EQ(pair_route(kinds[i], kinds[j]), pair_route(kinds[j], kinds[i])) << i << ", " << j;
    }
  EXPECT_EQ(plane_route(K::Convex), R::Convex);
  EXPECT_EQ(plane_route(K::WallPiece), R::Convex);
  EXPECT_EQ(plane_route(K::Surface), R::Patches);
  EXPECT_EQ(plane_route(K::Shell), R::Shell);
}

}  // namespace
}  // namespace gjkdem::dem
