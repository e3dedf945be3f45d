// classify_depth() against penetration(), its definition: apart when
// penetration() finds no common point, beyond `depth` when its depth is
// larger, within otherwise. The cheap proofs (the overlap test's enclosing
// tetrahedron; with margins, the test on shrunk margins) must never claim
// what EPA denies. Every property family (polytopes, boxes, spheres,
// capsules, curved cores, near-touching and sunk pairs, containment), as
// given and with margins added, at depths from 1e-12 of the size to half of
// it; disagreements are allowed only within the queries' own tolerance of
// the depth (or of touching).
#include <gtest/gtest.h>

#include <cmath>

#include "gjkdem/collide/query.hpp"
#include "property_families.hpp"

namespace gjkdem {
namespace {

using property::Family;

TEST(ClassifyDepth, AgreesWithPenetrationOnEveryFamily) {
  const Family families[] = {property::random_polytopes(), property::near_spherical_hulls(), property::boxes(),
                             property::parallel_faces(),   property::spheres(),              property::capsules(),
                             property::curved_size_ratios(), property::sunk_into_side(),
                             property::near_touching_curved(), property::kinked_maxima(), property::containment()};
  int checked = 0, beyond = 0, within = 0, apart = 0;
  for (const Family& f : families) {
    for (const property::Pair& given : f.pairs) {
      for (int rounded = 0; rounded < 2; ++rounded) {
        property::Pair p = given;
        const Real size = 2 * std::fmax(bounding_radius(p.a), bounding_radius(p.b));
        if (rounded) p.a.margin += 0.05 * size, p.b.margin += 0.02 * size;
        const PenetrationResult pen = penetration(p.a, p.pose_a(), p.b, p.pose_b());
        // The queries' own slack: EPA's tolerances, GJK's touching band.
        const Real slack = 1e-9 * size;
        for (const Real rel : {1e-12, 1e-6, 1e-3, 0.1, 0.5}) {
          const Real depth = rel * size;
          const DepthClass c = classify_depth(p.a, p.pose_a(), p.b, p.pose_b(), depth);
          ++checked;
          const std::string where = f.name + ": " + p.what + (rounded ? ", with margins" : "") +
                                    ", depth " + std::to_string(rel) + " of the size, EPA's depth " +
                                    std::to_string(pen.depth / size) + ", distance " + std::to_string(pen.distance / size);
          switch (c) {
            case DepthClass::Apart:
              ++apart;
              EXPECT_TRUE(!pen.intersect || pen.depth <= slack) << where;
              break;
            case DepthClass::Within:
              ++within;
              EXPECT_TRUE(pen.intersect || pen.distance <= slack) << where;
              EXPECT_LE(pen.depth, depth + slack) << where;
              break;
            case DepthClass::Beyond:
              ++beyond;
              EXPECT_TRUE(pen.intersect) << where;
              EXPECT_GT(pen.depth, depth - slack) << where;
              break;
          }
        }
      }
    }
  }
  // Each answer is met many times over: the test cannot pass on one of them.
  EXPECT_GT(beyond, 500);
  EXPECT_GT(within, 200);
  EXPECT_GT(apart, 500);
  EXPECT_GT(checked, 3000);
}

}  // namespace
}  // namespace gjkdem
