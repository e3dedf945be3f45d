// Not built here: it compiles against the engine before issue 10 (commit 8c209e6).
// Used for docs/benchmarks.md's free-fall comparison:
//   git worktree add /tmp/oldeng 8c209e6 && cp bench/legacy/free_fall_8c209e6.cpp /tmp/oldeng/bench/old_free_fall.cpp
//   echo 'add_executable(old_free_fall old_free_fall.cpp)' >> /tmp/oldeng/bench/CMakeLists.txt
//   echo 'target_link_libraries(old_free_fall PRIVATE gjkdem)' >> /tmp/oldeng/bench/CMakeLists.txt
//   cmake -S /tmp/oldeng -B /tmp/oldeng/build -DCMAKE_BUILD_TYPE=Release && cmake --build /tmp/oldeng/build --target old_free_fall
//   /tmp/oldeng/build/bench/old_free_fall THREADS STEPS
// The previous engine (8c209e6) on bench_dem_scaling --free-fall's world:
// 1,000 grains (50 random polyhedra from rng(1)) in a 10 x 10 x 10 lattice
// 1.5 sizes apart, random orientations (rng(7)), spins ~ N(0, 10) rad/s.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include "gjkdem/dem/generators.hpp"
#include "gjkdem/dem/world.hpp"
using namespace gjkdem;
using namespace gjkdem::dem;
// The draws of gjkdem::random_rotation, which 8c209e6 kept private.
Quat random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  Quat q;
  do q = {g(rng), g(rng), g(rng), g(rng)};
  while (!(std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z) > 1e-6));
  return normalized(q);
}
int main(int argc, char** argv) {
  const int threads = argc > 1 ? std::atoi(argv[1]) : 1, steps = argc > 2 ? std::atoi(argv[2]) : 2000;
  const Real size = 0.01;
  World w;
  w.model = ContactModel::Volume;
  w.threads = threads;
  w.materials.push_back({"rock", 2500, 1e7, 0.25, 0.3, 0.5});
  std::mt19937_64 rng(1);
  for (int t = 0; t < 50; ++t) w.templates.push_back(make_template(random_polyhedron(12, size, rng)));
  std::mt19937_64 rng7(7);
  for (int i = 0; i < 1000; ++i) {
    Body b;
    b.id = i;
    b.shape = i % 50;
    b.position = Vec3{Real(i % 10), Real(i / 10 % 10), Real(i / 100)} * (1.5 * size);
    b.orientation = random_rotation(rng7);
    w.bodies.push_back(b);
  }
  std::normal_distribution<double> spin(0, 10);
  for (Body& b : w.bodies) {
    const Vec3 m = w.templates[b.shape].principal.moments * 2500;
    b.angular_momentum = rotate(b.orientation, hadamard(m, Vec3{spin(rng7), spin(rng7), spin(rng7)}));
  }
  const Real dt = critical_time_step(w);
  step(w, dt);
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < steps; ++i) step(w, dt);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("previous engine, free fall: %zu grains, %d steps of %.3g s: %.4f us per particle-step; %d contacts\n",
              w.bodies.size(), steps, dt, 1e6 * s / steps / 1000.0, w.last_contacts);
}
