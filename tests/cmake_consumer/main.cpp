// Uses a convex query, a surface overlap and a DEM step from the installed
// library; prints what it found.
#include <cstdio>

#include "gjkdem/collide/query.hpp"
#include "gjkdem/contact/surface_overlap.hpp"
#include "gjkdem/dem/world_builder.hpp"

int main() {
  using namespace gjkdem;
  const Shape ball = make_sphere(1);
  const DistanceResult d = distance(ball, Transform{}, ball, Transform::from({3, 0, 0}, Quat{}));
  const std::vector<Vec3> v{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const std::vector<TriangleIndices> t{{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  const SurfaceOverlap o = surface_overlap(make_surface(v, t), make_surface(v, t));
  std::printf("distance %.3f tetrahedron overlap %.4f\n", d.distance, o.volume);
  return d.distance > 0.99 && d.distance < 1.01 && o.volume > 0.166 && o.volume < 0.167 ? 0 : 1;
}
