#include "gjkdem/io/query_jsonl.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace gjkdem::io {
namespace {

std::string error_of(const std::string& line) {
  std::string id;
  try {
    parse_pair(line, id);
  } catch (const QueryFormatError& e) {
    return e.what();
  }
  return "";
}

TEST(QueryJsonl, ParsesEveryShapeType) {
  const std::string line = R"({"id":"x","a":{"type":"box","center":[1,2,3],"half_extents":[1,1,1],"rotation":[1,0,0,0]},
    "b":{"type":"superellipsoid","center":[0,0,0],"radii":[1,2,3],"exponents":[0.5,1.5],"margin":0.1}})";
  std::string id;
  const PairInput p = parse_pair(line, id);
  EXPECT_EQ(p.id_json, "\"x\"");
  EXPECT_TRUE(std::holds_alternative<Box>(p.a.shape.core));
  EXPECT_EQ(p.a.pose.translation, (Vec3{1, 2, 3}));
  EXPECT_DOUBLE_EQ(p.b.shape.margin, 0.1);
  for (const char* s : {R"({"type":"sphere","center":[0,0,0],"radius":1})", R"({"type":"ellipsoid","center":[0,0,0],"radii":[1,2,3]})",
                        R"({"type":"capsule","p0":[0,0,0],"p1":[1,0,0],"radius":0.5})",
                        R"({"type":"cylinder","center":[0,0,0],"radius":1,"half_height":2})",
                        R"({"type":"cone","center":[0,0,0],"radius":1,"half_height":2})",
                        R"({"type":"triangle","vertices":[[0,0,0],[1,0,0],[0,1,0]]})",
                        R"({"type":"polytope","vertices":[[1e6,0,0]]})"})
    EXPECT_NO_THROW(parse_shape(s)) << s;
}

TEST(QueryJsonl, MeshesAreCheckedSurfacesAndPairWithFlatFacedSolids) {
  const std::string tet = R"({"type":"mesh","vertices":[[0,0,0],[1,0,0],[0,1,0],[0,0,1]],"triangles":[[0,2,1],[0,1,3],[0,3,2],[1,2,3]]})";
  std::string id;
  const PairInput two = parse_pair(R"({"id":1,"a":)" + tet + R"(,"b":)" + tet + "}", id);
  ASSERT_TRUE(two.a.surface && two.b.surface);
  EXPECT_NEAR(two.a.surface->volume, 1.0 / 6, 1e-15);
  // A box becomes its hull's surface, where it is.
  const PairInput box = parse_pair(R"({"id":2,"a":)" + tet + R"(,"b":{"type":"box","center":[5,0,0],"half_extents":[1,2,3]}})", id);
  ASSERT_TRUE(box.b.surface);
  EXPECT_NEAR(box.b.surface->volume, 48, 1e-12);
  EXPECT_NEAR(box.b.surface->box.lo.x, 4, 1e-15);
  EXPECT_NE(error_of(R"({"id":3,"a":)" + tet + R"(,"b":{"type":"sphere","center":[0,0,0],"radius":1}})").find("flat faces"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"id":4,"a":{"type":"mesh","vertices":[[0,0,0],[1,0,0],[0,1,0],[0,0,1]],"triangles":[[0,2,1],[0,1,3],[0,3,2],[1,3,2]]},"b":)" + tet + "}")
                .find("a is not a closed surface: triangles"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"id":5,"a":)" + tet + R"(,"b":{"type":"mesh","vertices":[[0,0,0]],"triangles":[[0,0,1]]}})").find("b.triangles[0]"),
            std::string::npos);
}

TEST(QueryJsonl, AMeshIsNoConvexShape) {
  for (const ShapeFrame frame : {ShapeFrame::World, ShapeFrame::Own})
    EXPECT_THROW(parse_shape(R"({"type":"mesh","vertices":[[0,0,0],[1,0,0],[0,1,0],[0,0,1]],"triangles":[[0,2,1],[0,1,3],[0,3,2],[1,2,3]]})",
                             frame),
                 QueryFormatError);
}

TEST(QueryJsonl, PolytopesAreRecentredForPrecision) {
  const PlacedInput p = parse_shape(R"({"type":"polytope","vertices":[[1e6,1e6,1e6],[1000001,1e6,1e6]]})");
  EXPECT_EQ(p.pose.translation, (Vec3{1e6 + 0.5, 1e6, 1e6}));
  EXPECT_DOUBLE_EQ(bounding_radius(p.shape), 0.5);
}

TEST(QueryJsonl, BadLinesNameTheProblem) {
  EXPECT_NE(error_of("{not json").find("not valid JSON"), std::string::npos);
  EXPECT_NE(error_of(R"({"id":1,"a":{"type":"blob"},"b":{}})").find("unknown type 'blob'"), std::string::npos);
  EXPECT_NE(error_of(R"({"id":1,"a":{"type":"sphere","center":[0,0,0],"radius":-1},"b":{"type":"sphere","center":[0,0,0],"radius":1}})")
                .find("a.radius must be >= 0"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"id":1,"a":{"type":"sphere","center":[0,0],"radius":1},"b":{}})").find("a.center"), std::string::npos);
  EXPECT_NE(error_of(R"({"id":1,"a":{"type":"polytope","vertices":[]},"b":{}})").find("non-empty"), std::string::npos);
  EXPECT_NE(error_of(R"({"id":1,"a":{"type":"box","center":[0,0,0],"half_extents":[1,1,1],"rotation":[2,0,0,0]},"b":{}})")
                .find("unit quaternion"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"id":1,"a":{"type":"sphere","center":[0,0,0],"radius":1,"colour":"red"},"b":{}})")
                .find("unknown key 'colour'"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"id":1,"a":{"type":"superellipsoid","center":[0,0,0],"radii":[1,1,1],"exponents":[3,1]},"b":{}})")
                .find("(0, 2]"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"id":1,"a":{"type":"sphere","center":[0,0,0],"radius":1}})").find("'a' and 'b'"), std::string::npos);
  EXPECT_NE(error_of(R"([1,2])").find("JSON object"), std::string::npos);
}

TEST(QueryJsonl, ResultAndErrorLinesAreJson) {
  PenetrationResult r;
  r.intersect = true;
  r.depth = 0.5;
  r.normal = {0, 0, 1};
  const std::string s = format_result("\"p\"", r);
  EXPECT_NE(s.find("\"intersect\":true"), std::string::npos);
  EXPECT_NE(s.find("\"overlap_volume\":null"), std::string::npos);
  EXPECT_EQ(format_error("7", "line 3: bad \"x\""), R"({"id":7,"error":"line 3: bad \"x\""})");
  EXPECT_TRUE(is_skipped_line("  # comment"));
  EXPECT_TRUE(is_skipped_line("   "));
  EXPECT_FALSE(is_skipped_line(" {}"));
}

// An answer that is not finite is thrown, never written: the line loop turns
// it into an error line naming the input line, as every other refusal.
TEST(QueryJsonl, AnAnswerThatIsNotFiniteIsThrownForTheLineLoop) {
  PenetrationResult r;
  r.distance = std::numeric_limits<Real>::infinity();
  EXPECT_THROW(format_result("1", r), std::range_error);
  PenetrationResult fine;
  OverlapFields f;
  f.computed = true;
  f.volume = std::nan("");
  EXPECT_THROW(format_result("1", fine, f), std::range_error);
  SurfaceOverlap o;
  o.intersect = true;
  o.volume = 1;
  o.patches.push_back({});
  o.patches[0].volume = std::numeric_limits<Real>::infinity();
  EXPECT_THROW(format_surface_result("1", o, nullptr, 1), std::range_error);
  o.patches[0].volume = 1;
  EXPECT_NO_THROW(format_surface_result("1", o, nullptr, 1));
}

}  // namespace
}  // namespace gjkdem::io
