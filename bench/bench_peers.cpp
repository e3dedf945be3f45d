// Peer comparison: the same polytope pairs timed, in one process run, with
// gjkdem, libccd (GJK and MPR), FCL and Bullet (float64 build), and each peer's
// answers compared with gjkdem's (which the tests check against brute-force
// oracles). Prints a Markdown table of median ns per query, the ratio
// peer / gjkdem, and the number of pairs where the peer disagrees.
//
//   bench_peers [--pairs N] [--repeat R] [--in FILE.jsonl]
//
// Without --in it times two generated sets (8-64 and 200-2000 vertices); with
// --in, the polytope pairs of that file (query-format.md) instead.
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpa2.h>
#include <ccd/ccd.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <memory>
#include <string>

#include "gjkdem/collide/query.hpp"
#include "gjkdem/io/query_jsonl.hpp"
#include "gjkdem/shape/convex_hull.hpp"
#include "random_pairs.hpp"

namespace gjkdem::bench {
namespace {

struct CcdObject {
  std::vector<Vec3> world;
  Vec3 centre;
};

void ccd_support(const void* obj, const ccd_vec3_t* dir, ccd_vec3_t* out) {
  const auto* o = static_cast<const CcdObject*>(obj);
  const Vec3 d{dir->v[0], dir->v[1], dir->v[2]};
  const Vec3* best = &o->world[0];
  double best_dot = dot(*best, d);
  for (const Vec3& v : o->world)
    if (dot(v, d) > best_dot) { best_dot = dot(v, d); best = &v; }
  ccdVec3Set(out, best->x, best->y, best->z);
}

void ccd_center(const void* obj, ccd_vec3_t* out) {
  const auto* o = static_cast<const CcdObject*>(obj);
  ccdVec3Set(out, o->centre.x, o->centre.y, o->centre.z);
}

struct PeerPair {
  PolytopePair p;
  CcdObject ccd_a, ccd_b;
  std::unique_ptr<btConvexHullShape> bt_a, bt_b;
  btTransform bt_pose_a, bt_pose_b;
  std::unique_ptr<fcl::CollisionObjectd> fcl_a, fcl_b;
  PenetrationResult truth;  // gjkdem's full answer
};

std::unique_ptr<btConvexHullShape> bullet_hull(const std::vector<Vec3>& local) {
  auto s = std::make_unique<btConvexHullShape>();
  for (const Vec3& v : local) s->addPoint(btVector3(v.x, v.y, v.z), false);
  s->recalcLocalAabb();
  s->setMargin(0);  // the default 0.04 margin would change the shape
  return s;
}

std::unique_ptr<fcl::CollisionObjectd> fcl_object(const std::vector<Vec3>& local, const Vec3& pos) {
  const ConvexHull h = convex_hull(local);
  auto verts = std::make_shared<std::vector<fcl::Vector3d>>();
  for (const Vec3& v : h.vertices) verts->emplace_back(v.x, v.y, v.z);
  auto faces = std::make_shared<std::vector<int>>();
  for (const auto& t : h.triangles) faces->insert(faces->end(), {3, t[0], t[1], t[2]});
  auto geom = std::make_shared<fcl::Convexd>(verts, static_cast<int>(h.triangles.size()), faces);
  fcl::Transform3d tf = fcl::Transform3d::Identity();
  tf.translation() = fcl::Vector3d(pos.x, pos.y, pos.z);
  return std::make_unique<fcl::CollisionObjectd>(geom, tf);
}

std::vector<PeerPair> make_peer_pairs(std::vector<PolytopePair> pairs) {
  std::vector<PeerPair> out;
  for (auto& p : pairs) {
    // FCL needs a solid hull; skip flat or degenerate inputs for every peer alike.
    if (convex_hull(p.local_a).dimension != HullDimension::Solid ||
        convex_hull(p.local_b).dimension != HullDimension::Solid)
      continue;
    PeerPair q;
    q.p = std::move(p);
    for (const Vec3& v : q.p.local_a) q.ccd_a.world.push_back(v + q.p.pose_a.translation);
    for (const Vec3& v : q.p.local_b) q.ccd_b.world.push_back(v + q.p.pose_b.translation);
    q.ccd_a.centre = q.p.pose_a.translation;
    q.ccd_b.centre = q.p.pose_b.translation;
    q.bt_a = bullet_hull(q.p.local_a);
    q.bt_b = bullet_hull(q.p.local_b);
    const Vec3 ta = q.p.pose_a.translation, tb = q.p.pose_b.translation;
    q.bt_pose_a = btTransform(btQuaternion::getIdentity(), btVector3(ta.x, ta.y, ta.z));
    q.bt_pose_b = btTransform(btQuaternion::getIdentity(), btVector3(tb.x, tb.y, tb.z));
    q.fcl_a = fcl_object(q.p.local_a, ta);
    q.fcl_b = fcl_object(q.p.local_b, tb);
    q.truth = penetration(q.p.a, q.p.pose_a, q.p.b, q.p.pose_b);
    out.push_back(std::move(q));
  }
  return out;
}

std::vector<PolytopePair> pairs_from_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::vector<PolytopePair> pairs;
  std::string line;
  while (std::getline(in, line)) {
    if (io::is_skipped_line(line)) continue;
    std::string id;
    const io::PairInput in_pair = io::parse_pair(line, id);
    const auto* pa = std::get_if<Polytope>(&in_pair.a.shape.core);
    const auto* pb = std::get_if<Polytope>(&in_pair.b.shape.core);
    if (!pa || !pb || in_pair.a.shape.margin > 0 || in_pair.b.shape.margin > 0) continue;
    PolytopePair p;
    p.local_a.assign(pa->data->vertices.begin(), pa->data->vertices.end());
    p.local_b.assign(pb->data->vertices.begin(), pb->data->vertices.end());
    p.pose_a = in_pair.a.pose;
    p.pose_b = in_pair.b.pose;
    p.a = in_pair.a.shape;
    p.b = in_pair.b.shape;
    p.size = 2 * std::fmax(bounding_radius(p.a), bounding_radius(p.b));
    pairs.push_back(std::move(p));
  }
  return pairs;
}

// Answer of one peer on one pair, for the agreement check.
struct Answer {
  bool intersect = false;
  double value = 0;  // distance or depth, by query
  bool valid = true;
};

using PeerFn = std::function<Answer(const PeerPair&)>;

struct Timing {
  double ns = 0;
  int disagree = 0;
  int checked = 0;
};

volatile double g_sink = 0;

Timing time_peer(const std::vector<const PeerPair*>& pairs, const PeerFn& fn, int repeat, const char* query) {
  Timing t;
  for (const PeerPair* p : pairs) {  // warm-up pass doubles as the agreement check
    const Answer a = fn(*p);
    const PenetrationResult& r = p->truth;
    const double gap = r.intersect ? r.depth : r.distance;
    const double tol = 1e-6 * std::fabs(gap) + 1e-9 * p->p.size;
    ++t.checked;
    bool ok = a.valid;
    if (std::strcmp(query, "intersect") == 0) ok = ok && (gap <= tol || a.intersect == r.intersect);
    else if (std::strcmp(query, "distance") == 0) ok = ok && std::fabs(a.value - r.distance) <= tol;
    else ok = ok && std::fabs(a.value - r.depth) <= tol;
    t.disagree += !ok;
  }
  std::vector<double> passes;
  for (int k = 0; k < repeat; ++k) {
    double acc = 0;
    const auto t0 = std::chrono::steady_clock::now();
    for (const PeerPair* p : pairs) acc += fn(*p).value;
    const auto t1 = std::chrono::steady_clock::now();
    g_sink = g_sink + acc;
    passes.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count() / static_cast<double>(pairs.size()));
  }
  std::sort(passes.begin(), passes.end());
  t.ns = passes[passes.size() / 2];
  return t;
}

ccd_t ccd_setup() {
  ccd_t c;
  CCD_INIT(&c);
  c.support1 = ccd_support;
  c.support2 = ccd_support;
  c.center1 = ccd_center;
  c.center2 = ccd_center;
  c.max_iterations = 500;
  return c;
}

void run_set(const char* name, const std::vector<PeerPair>& all, int repeat) {
  std::vector<const PeerPair*> every, hitting, missing;
  for (const PeerPair& p : all) {
    every.push_back(&p);
    (p.truth.intersect ? hitting : missing).push_back(&p);
  }
  std::printf("\n### %s: %zu pairs (%zu intersecting)\n\n", name, every.size(), hitting.size());
  std::printf("| query | code | ns/query | ratio to gjkdem | disagrees with gjkdem |\n|---|---|---|---|---|\n");
  const ccd_t ccd = ccd_setup();
  struct Row { const char* query; const char* code; const std::vector<const PeerPair*>* set; PeerFn fn; };
  const std::vector<Row> rows = {
      {"intersect", "gjkdem GJK", &every, [](const PeerPair& q) {
         const bool hit = intersect(q.p.a, q.p.pose_a, q.p.b, q.p.pose_b);
         return Answer{hit, double(hit)}; }},
      {"intersect", "libccd GJK", &every, [&ccd](const PeerPair& q) {
         const bool hit = ccdGJKIntersect(&q.ccd_a, &q.ccd_b, &ccd);
         return Answer{hit, double(hit)}; }},
      {"intersect", "libccd MPR", &every, [&ccd](const PeerPair& q) {
         const bool hit = ccdMPRIntersect(&q.ccd_a, &q.ccd_b, &ccd);
         return Answer{hit, double(hit)}; }},
      {"distance", "gjkdem GJK", &missing, [](const PeerPair& q) {
         const DistanceResult d = distance(q.p.a, q.p.pose_a, q.p.b, q.p.pose_b);
         return Answer{d.intersect, d.distance}; }},
      {"distance", "Bullet GJK", &missing, [](const PeerPair& q) {
         btGjkEpaSolver2::sResults res;
         const bool sep = btGjkEpaSolver2::Distance(q.bt_a.get(), q.bt_pose_a, q.bt_b.get(), q.bt_pose_b,
                                                    btVector3(1, 0, 0), res);
         return Answer{!sep, sep ? double(res.distance) : 0.0, sep}; }},
      {"distance", "FCL (libccd GJK)", &missing, [](const PeerPair& q) {
         fcl::DistanceRequestd req;
         fcl::DistanceResultd res;
         fcl::distance(q.fcl_a.get(), q.fcl_b.get(), req, res);
         return Answer{res.min_distance <= 0, res.min_distance}; }},
      {"penetration", "gjkdem GJK+EPA", &hitting, [](const PeerPair& q) {
         const PenetrationResult r = penetration(q.p.a, q.p.pose_a, q.p.b, q.p.pose_b);
         return Answer{r.intersect, r.depth}; }},
      {"penetration", "libccd MPR", &hitting, [&ccd](const PeerPair& q) {
         ccd_real_t depth = 0;
         ccd_vec3_t dir, pos;
         const int rc = ccdMPRPenetration(&q.ccd_a, &q.ccd_b, &ccd, &depth, &dir, &pos);
         return Answer{rc == 0, double(depth), rc == 0}; }},
      {"penetration", "libccd GJK+EPA", &hitting, [&ccd](const PeerPair& q) {
         ccd_real_t depth = 0;
         ccd_vec3_t dir, pos;
         const int rc = ccdGJKPenetration(&q.ccd_a, &q.ccd_b, &ccd, &depth, &dir, &pos);
         return Answer{rc == 0, double(depth), rc == 0}; }},
      {"penetration", "Bullet GJK+EPA", &hitting, [](const PeerPair& q) {
         btGjkEpaSolver2::sResults res;
         const bool pen = btGjkEpaSolver2::Penetration(q.bt_a.get(), q.bt_pose_a, q.bt_b.get(), q.bt_pose_b,
                                                       btVector3(1, 0, 0), res, false);
         return Answer{pen, pen ? -double(res.distance) : 0.0, pen}; }},
      {"penetration", "FCL (libccd GJK+EPA)", &hitting, [](const PeerPair& q) {
         fcl::CollisionRequestd req(1, true);
         fcl::CollisionResultd res;
         fcl::collide(q.fcl_a.get(), q.fcl_b.get(), req, res);
         const bool hit = res.numContacts() > 0;
         return Answer{hit, hit ? res.getContact(0).penetration_depth : 0.0, hit}; }},
  };
  double base_ns = 0;
  for (const Row& row : rows) {
    if (row.set->empty()) continue;
    const Timing t = time_peer(*row.set, row.fn, repeat, row.query);
    if (std::strncmp(row.code, "gjkdem", 6) == 0) base_ns = t.ns;
    std::printf("| %s | %s | %.0f | %.2f | %d of %d |\n", row.query, row.code, t.ns, t.ns / base_ns, t.disagree,
                t.checked);
  }
}

}  // namespace
}  // namespace gjkdem::bench

int main(int argc, char** argv) {
  using namespace gjkdem::bench;
  int count = 400, repeat = 15;
  std::string in;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--pairs" && i + 1 < argc) count = std::atoi(argv[++i]);
    else if (a == "--repeat" && i + 1 < argc) repeat = std::atoi(argv[++i]);
    else if (a == "--in" && i + 1 < argc) in = argv[++i];
    else {
      std::fprintf(stderr, "usage: bench_peers [--pairs N] [--repeat R] [--in FILE.jsonl]\n");
      return 2;
    }
  }
  if (count < 1 || repeat < 1) {
    std::fprintf(stderr, "bench_peers: --pairs and --repeat must be >= 1\n");
    return 2;
  }
  try {
    if (!in.empty()) {
      run_set(in.c_str(), make_peer_pairs(pairs_from_file(in)), repeat);
    } else {
      run_set("random polytopes, 8-64 vertices", make_peer_pairs(random_pairs(count, 8, 64, 11)), repeat);
      run_set("random polytopes, 200-2000 vertices", make_peer_pairs(random_pairs(count / 8, 200, 2000, 12)), repeat);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_peers: %s\n", e.what());
    return 1;
  }
  return 0;
}
