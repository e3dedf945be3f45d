#pragma once
// Seeded random polytope pairs shared by the benchmarks: rock-like clouds
// (points on a randomly stretched sphere, some inside), placed so that about
// half of the pairs intersect.
#include <random>
#include <vector>

#include "gjkdem/shape/shape.hpp"

namespace gjkdem::bench {

struct PolytopePair {
  std::vector<Vec3> local_a, local_b;  ///< vertices about each body's centre
  Transform pose_a, pose_b;            ///< translation only: vertices are pre-rotated
  Shape a, b;
  Real size = 1;
};

inline std::vector<Vec3> random_rock(std::mt19937_64& rng, int n) {
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(0.6, 1.4);
  const Vec3 stretch{u(rng), u(rng), u(rng)};
  std::vector<Vec3> pts;
  for (int i = 0; i < n; ++i) {
    const Vec3 d = normalized(Vec3{g(rng), g(rng), g(rng)});
    const double r = i % 8 == 7 ? 0.5 : 1.0;  // an eighth of the points inside
    pts.push_back(hadamard(d, stretch) * r);
  }
  return pts;
}

/// `count` pairs with vertex counts drawn from [min_vertices, max_vertices].
inline std::vector<PolytopePair> random_pairs(int count, int min_vertices, int max_vertices, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> nv(min_vertices, max_vertices);
  std::uniform_real_distribution<double> u(-1, 1), dist(1.0, 2.6);
  std::normal_distribution<double> g;
  std::vector<PolytopePair> pairs;
  for (int i = 0; i < count; ++i) {
    PolytopePair p;
    p.local_a = random_rock(rng, nv(rng));
    p.local_b = random_rock(rng, nv(rng));
    const Vec3 offset = normalized(Vec3{g(rng), g(rng), g(rng)}) * dist(rng);
    const Vec3 base = Vec3{u(rng), u(rng), u(rng)} * 10.0;
    p.pose_a = Transform::from(base, {});
    p.pose_b = Transform::from(base + offset, {});
    p.a.core = make_polytope(p.local_a);
    p.b.core = make_polytope(p.local_b);
    p.size = 2 * std::fmax(bounding_radius(p.a), bounding_radius(p.b));
    pairs.push_back(std::move(p));
  }
  return pairs;
}

}  // namespace gjkdem::bench
