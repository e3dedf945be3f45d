// Cost of a DEM step per particle on a settled bed, at growing particle
// counts (issue 4's benchmark): 1,000 random 12-vertex polyhedra of 1 cm
// (50 shared templates; or cubes) are poured into a 10 x 10 cm box of plane
// walls and settled under gravity and the volume law; the settled block is
// then tiled N / 1000 times side by side in one larger box, the seams are
// given `--settle` steps to come to rest (not timed), and `--steps` steps
// are timed. Memory per particle is the growth of
// the resident set from before the world was built to after the timed steps,
// divided by N (shapes are shared, so it is bodies, contact histories, pair
// caches and the step's working arrays).
//
//   bench_dem_scaling [--shape poly|cube] [--threads T] [--export PREFIX] [--block FILE] N [N ...]
//
// `--block FILE` keeps the settled block (7 min of the 2-core machine): read
// when FILE exists, written after settling otherwise.
//
// Prints one line per N: contacts per particle, wall time per step,
// microseconds per particle-step, bytes per particle (growth of the resident
// set), and the world's arrays split into bytes per body and per contact. `--export PREFIX` writes
// each bed (PREFIX<N>.txt) for bench/yade_bed.py, which runs it in Yade.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "gjkdem/dem/generators.hpp"
#include "gjkdem/dem/world.hpp"

using namespace gjkdem;
using namespace gjkdem::dem;

namespace {

constexpr Real kSize = 0.01;      // m, diameter of the particles' bounding spheres
constexpr int kBlockCount = 1000;  // particles settled once, then tiled
constexpr Real kBlockSide = 10 * kSize;

long resident_bytes() {
  std::ifstream statm("/proc/self/statm");
  long pages = 0, resident = 0;
  statm >> pages >> resident;
  return resident * 4096;
}

void add_box_walls(World& w, Real x_side, Real y_side) {
  const std::uint64_t id = std::uint64_t(1) << 62;
  w.planes.clear();
  w.planes.push_back({id, {0, 0, 0}, {0, 0, 1}, 0});
  w.planes.push_back({id + 1, {0, 0, 0}, {1, 0, 0}, 0});
  w.planes.push_back({id + 2, {x_side, 0, 0}, {-1, 0, 0}, 0});
  w.planes.push_back({id + 3, {0, 0, 0}, {0, 1, 0}, 0});
  w.planes.push_back({id + 4, {0, y_side, 0}, {0, -1, 0}, 0});
}

// 1,000 particles poured into a 10 x 10 cm box and settled under gravity
// (0.5 s of simulated time): the block every bed is tiled from.
World settled_block(bool cubes, int threads, const std::string& cache) {
  World w;
  w.model = ContactModel::Volume;
  w.threads = threads;
  w.materials.push_back({"rock", 2500, 1e7, 0.25, 0.3, 0.5});
  std::mt19937_64 rng(1);
  if (cubes) w.templates.push_back(make_template(platonic("cube", kSize)));
  else
    for (int t = 0; t < 50; ++t) w.templates.push_back(make_template(random_polyhedron(12, kSize, rng)));
  add_box_walls(w, kBlockSide, kBlockSide);
  if (!cache.empty()) {  // a block settled by an earlier run with the same templates
    std::ifstream in(cache);
    Body b;
    while (in >> b.id >> b.shape >> b.position.x >> b.position.y >> b.position.z >> b.orientation.w >>
           b.orientation.x >> b.orientation.y >> b.orientation.z) {
      if (b.shape >= w.templates.size()) {
        std::fprintf(stderr, "%s: shape %u of body %llu does not exist; it was settled with other shapes\n",
                     cache.c_str(), b.shape, static_cast<unsigned long long>(b.id));
        std::exit(2);
      }
      w.bodies.push_back(b);
    }
    if (!w.bodies.empty()) return w;
  }
  const auto places = place_in_region(w, {0, 0, 0}, {kBlockSide, kBlockSide, 1.4 * kBlockSide}, kSize,
                                      kBlockCount, rng);
  for (std::size_t i = 0; i < places.size(); ++i) {
    Body b;
    b.id = i;
    b.shape = static_cast<std::uint32_t>(i % w.templates.size());
    b.position = places[i].position;
    b.orientation = places[i].rotation;
    w.bodies.push_back(b);
  }
  const Real dt = critical_time_step(w);
  while (w.time < 0.5) step(w, dt);
  if (!cache.empty()) {
    std::ofstream out(cache);
    out.precision(17);
    for (const Body& b : w.bodies)
      out << b.id << ' ' << b.shape << ' ' << b.position.x << ' ' << b.position.y << ' ' << b.position.z << ' '
          << b.orientation.w << ' ' << b.orientation.x << ' ' << b.orientation.y << ' ' << b.orientation.z << '\n';
  }
  return w;
}

// The block repeated tiles_x by tiles_y times side by side, in one box.
World tiled_bed(const World& block, int tiles_x, int tiles_y) {
  World w;
  w.model = block.model;
  w.threads = block.threads;
  w.materials = block.materials;
  w.templates = block.templates;
  add_box_walls(w, tiles_x * kBlockSide, tiles_y * kBlockSide);
  for (int ty = 0; ty < tiles_y; ++ty)
    for (int tx = 0; tx < tiles_x; ++tx)
      for (const Body& source : block.bodies) {
        Body b;
        b.id = w.bodies.size();
        b.shape = source.shape;
        b.position = source.position + Vec3{tx * kBlockSide, ty * kBlockSide, 0};
        b.orientation = source.orientation;
        w.bodies.push_back(b);
      }
  return w;
}

// Every body as its world-frame hull vertices, one line each, for
// bench/yade_bed.py: "side_x side_y" on the first line.
void export_bed(const World& w, const std::string& file, Real side_x, Real side_y) {
  std::ofstream out(file);
  out.precision(17);
  out << side_x << ' ' << side_y << '\n';
  for (const Body& b : w.bodies) {
    const Transform pose = shape_pose(w, b);
    const Shape& s = w.templates[b.shape].shape;
    for (const Vec3& v : std::get<Polytope>(s.core).data->vertices) {
      const Vec3 x = apply(pose, v);
      out << x.x << ' ' << x.y << ' ' << x.z << ' ';
    }
    out << '\n';
  }
}

// Bytes held by the world's arrays (capacities), split into what grows with
// the bodies and what grows with the contacts.
struct Footprint {
  double per_body = 0, per_contact = 0;
};

Footprint footprint(const World& w) {
  double bodies = static_cast<double>(w.bodies.capacity() * sizeof(Body) + w.boxes.capacity() * sizeof(Aabb) +
                                      (w.sweep.order.capacity() + w.sweep.entries.capacity() +
                                       w.sweep.strip_begin.capacity() + w.sweep.cursor.capacity()) *
                                          sizeof(std::uint32_t));
  double contacts = static_cast<double>(w.pair_caches.capacity() * sizeof(PairCache) +
                                        w.candidates.capacity() * sizeof(BodyPair) +
                                        w.contacts.capacity() * sizeof(StepContact));
  for (const Body& b : w.bodies) contacts += static_cast<double>(b.history.capacity() * sizeof(ContactHistory));
  for (const auto& found : w.sweep.found) contacts += static_cast<double>(found.capacity() * sizeof(BodyPair));
  return {bodies / static_cast<double>(w.bodies.size()), contacts / std::max(1, w.last_contacts)};
}

}  // namespace

int main(int argc, char** argv) {
  bool cubes = false;
  int threads = 0, settle = 20, steps = 0;
  std::string export_prefix, block_cache;
  std::vector<int> counts;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--shape" && i + 1 < argc) cubes = std::strcmp(argv[++i], "cube") == 0;
    else if (a == "--threads" && i + 1 < argc) threads = std::atoi(argv[++i]);
    else if (a == "--settle" && i + 1 < argc) settle = std::atoi(argv[++i]);
    else if (a == "--steps" && i + 1 < argc) steps = std::atoi(argv[++i]);
    else if (a == "--export" && i + 1 < argc) export_prefix = argv[++i];
    else if (a == "--block" && i + 1 < argc) block_cache = argv[++i];
    else if (std::atoi(a.c_str()) >= kBlockCount && std::atoi(a.c_str()) % kBlockCount == 0) counts.push_back(std::atoi(a.c_str()));
    else {
      std::fprintf(stderr,
                   "usage: %s [--shape poly|cube] [--threads T] [--settle S] [--steps S] [--export PREFIX] [--block FILE] N [N ...]\n"
                   "  N: multiples of 1000 (default 1000 10000 100000)\n",
                   argv[0]);
      return 2;
    }
  }
  if (counts.empty()) counts = {1000, 10000, 100000};
  const auto t_block = std::chrono::steady_clock::now();
  const World block = settled_block(cubes, threads, block_cache);
  std::printf("block: %zu %s settled in %.1f s wall; %d contacts\n", block.bodies.size(), cubes ? "cubes" : "polyhedra",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t_block).count(), block.last_contacts);
  std::printf("%-8s %9s %9s %12s %14s %12s %12s %12s\n", "N", "contacts", "per_part", "ms/step", "us/part-step",
              "bytes/part", "arrays/body", "arrays/cont");
  for (const int n : counts) {
    const int tiles = n / kBlockCount;
    int tiles_x = 1;
    for (int t = 1; t * t <= tiles; ++t)
      if (tiles % t == 0) tiles_x = t;
    const int tiles_y = tiles / tiles_x;
    const long before = resident_bytes();
    World w = tiled_bed(block, tiles_x, tiles_y);
    const Real dt = critical_time_step(w);
    for (int i = 0; i < settle; ++i) step(w, dt);  // the tiles' seams come to rest
    if (!export_prefix.empty())
      export_bed(w, export_prefix + std::to_string(w.bodies.size()) + ".txt", tiles_x * kBlockSide, tiles_y * kBlockSide);
    const int timed = steps > 0 ? steps : std::max(10, static_cast<int>(4e5 / n));
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < timed; ++i) step(w, dt);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const long bytes = resident_bytes() - before;
    const std::size_t bodies = w.bodies.size();
    const Footprint arrays = footprint(w);
    // Contacts per particle: pair contacts count for both bodies, wall contacts for one.
    std::printf("%-8zu %9d %9.2f %12.3f %14.3f %12.0f %12.0f %12.0f\n", bodies, w.last_contacts,
                (2.0 * w.last_contacts - w.last_wall_contacts) / static_cast<double>(bodies), 1e3 * seconds / timed,
                1e6 * seconds / timed / static_cast<double>(bodies), static_cast<double>(bytes) / bodies,
                arrays.per_body, arrays.per_contact);
    std::fflush(stdout);
  }
  return 0;
}
