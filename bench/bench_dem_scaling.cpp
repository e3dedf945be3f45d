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
//
// Under `mpirun -np R` the timed steps run on R domains (dem::run_domains),
// with each rank's bodies, ghosts and traffic per step (docs/scaling.md).
//
// `--narrow` also times the narrow phase alone on each bed, one thread,
// over the step's candidate pairs of two bodies with the warm starts they
// have in the bed: per touching contact, the whole query (GJK's test, then
// the overlap region) and the GJK test alone; per candidate that does not
// touch, the query (issue 12's goal: under 5 us per contact).
//
//   bench_dem_scaling --free-fall [--threads T] [--steps S] [--export FILE] [--final FILE] [--dt-scale K]
//
// times 1,000 grains falling freely instead; `--export FILE` writes them (and
// FILE.spin, their angular velocities) for bench/yade_free_fall.py;
// `--final FILE` writes each grain's hull vertices at the end, world axes,
// from its centre of mass (how far it turned: bench/compare_rotation.py);
// `--dt-scale K` runs the same time in steps K times as long (K > 1, the
// critical step still exported) or as short (K < 1, a reference).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "gjkdem/collide/query.hpp"
#include "gjkdem/dem/domains.hpp"
#include "gjkdem/dem/narrow_phase.hpp"
#include "gjkdem/dem/world_builder.hpp"
#include "gjkdem/mpi/mpi_transport.hpp"
#include "gjkdem/shape/shape_factories.hpp"

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

void add_box_walls(WorldBuilder& b, std::uint32_t material, Real x_side, Real y_side) {
  b.add_plane({0, 0, 0}, {0, 0, 1}, material, "floor");
  b.add_plane({0, 0, 0}, {1, 0, 0}, material, "wall -x");
  b.add_plane({x_side, 0, 0}, {-1, 0, 0}, material, "wall +x");
  b.add_plane({0, 0, 0}, {0, 1, 0}, material, "wall -y");
  b.add_plane({0, y_side, 0}, {0, -1, 0}, material, "wall +y");
}

struct BlockBody {
  std::uint32_t shape = 0;  // index of the shared shape
  Vec3 position;            // centre of mass
  Quat orientation;         // principal frame
};

// A bed of bodies with the given states, all sharing the block's shapes, in a
// box of plane walls: built with the bodies anywhere, then set to the states
// (a settled bed overlaps, so the builder is told to accept that). Sides of
// 0: no walls.
Real g_skin = WorldSettings{}.box_skin;  // --skin

World bed(bool cubes, int threads, const std::vector<BlockBody>& bodies, Real x_side, Real y_side) {
  WorldSettings settings;
  settings.model = ContactModel::Volume;
  settings.threads = threads;
  settings.box_skin = g_skin;
  WorldBuilder b(settings);
  b.accept_initial_overlaps();
  const std::uint32_t rock = b.add_material({"rock", 2500, 1e7, 0.25, 0.3, 0.5});
  std::mt19937_64 rng(1);
  const int shapes = cubes ? 1 : 50;
  for (int t = 0; t < shapes; ++t)
    b.add_shape({cubes ? platonic("cube", kSize) : random_polyhedron(12, kSize, rng), {}}, "shape");
  if (x_side > 0) add_box_walls(b, rock, x_side, y_side);
  for (const BlockBody& body : bodies)
    b.add_body({.shared_shape = body.shape, .material = rock, .position = body.position});
  World w = b.build();
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    w.bodies[i].position = bodies[i].position;
    w.bodies[i].orientation = bodies[i].orientation;
  }
  return w;
}

// 1,000 particles poured into a 10 x 10 cm box and settled under gravity
// (0.5 s of simulated time): the block every bed is tiled from.
std::vector<BlockBody> settled_block(bool cubes, int threads, const std::string& cache) {
  std::vector<BlockBody> block;
  const std::size_t shapes = cubes ? 1 : 50;
  if (!cache.empty()) {  // a block settled by an earlier run with the same shapes
    std::ifstream in(cache);
    BlockBody b;
    std::uint64_t id = 0;  // the file's first column (the old engine's ids), unused
    while (in >> id >> b.shape >> b.position.x >> b.position.y >> b.position.z >> b.orientation.w >> b.orientation.x >>
           b.orientation.y >> b.orientation.z) {
      if (b.shape >= shapes) {
        std::fprintf(stderr, "%s: shape %u does not exist; it was settled with other shapes\n", cache.c_str(), b.shape);
        std::exit(2);
      }
      block.push_back(b);
    }
    if (!block.empty()) return block;
  }
  // Cells one size apart, filled from the bottom, random orientations.
  std::mt19937_64 rng(7);
  const int per_side = static_cast<int>(kBlockSide / kSize);
  for (int i = 0; static_cast<int>(block.size()) < kBlockCount; ++i) {
    const int x = i % per_side, y = i / per_side % per_side, z = i / (per_side * per_side);
    block.push_back({static_cast<std::uint32_t>(i % shapes), Vec3{x + 0.5, y + 0.5, z + 0.5} * (1.4 * kSize),
                     random_rotation(rng)});
  }
  for (BlockBody& b : block) b.position = {b.position.x / 1.4, b.position.y / 1.4, b.position.z};
  World w = bed(cubes, threads, block, kBlockSide, kBlockSide);
  const Real dt = critical_time_step(w);
  while (w.time < 0.5) step(w, dt);
  for (std::size_t i = 0; i < block.size(); ++i) block[i] = {block[i].shape, w.bodies[i].position, w.bodies[i].orientation};
  if (!cache.empty()) {
    std::ofstream out(cache);
    out.precision(17);
    for (std::size_t i = 0; i < block.size(); ++i) {
      const BlockBody& b = block[i];
      out << i << ' ' << b.shape << ' ' << b.position.x << ' ' << b.position.y << ' ' << b.position.z << ' ' << b.orientation.w
          << ' ' << b.orientation.x << ' ' << b.orientation.y << ' ' << b.orientation.z << '\n';
    }
  }
  return block;
}

// The block repeated tiles_x by tiles_y times side by side, in one box.
World tiled_bed(bool cubes, int threads, const std::vector<BlockBody>& block, int tiles_x, int tiles_y) {
  std::vector<BlockBody> bodies;
  for (int ty = 0; ty < tiles_y; ++ty)
    for (int tx = 0; tx < tiles_x; ++tx)
      for (const BlockBody& b : block)
        bodies.push_back({b.shape, b.position + Vec3{tx * kBlockSide, ty * kBlockSide, 0}, b.orientation});
  return bed(cubes, threads, bodies, tiles_x * kBlockSide, tiles_y * kBlockSide);
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
  const StepWorkspace& k = w.work;
  const BoxCache& boxes = w.search.boxes;
  double bodies = static_cast<double>(
      w.bodies.capacity() * sizeof(Body) + boxes.boxes.capacity() * sizeof(Aabb) +
      boxes.anchor_position.capacity() * sizeof(Vec3) + boxes.anchor_orientation.capacity() * sizeof(Quat) +
      boxes.moved.capacity() * sizeof(Real) + k.moving.capacity() * sizeof(std::uint32_t) + k.moving_boxes.capacity() * sizeof(Aabb) +
      (k.sweep.order.capacity() + k.sweep.entries.capacity() + k.sweep.strip_begin.capacity() +
       k.sweep.cursor.capacity()) * sizeof(std::uint32_t));
  double contacts = static_cast<double>(w.pairs.capacity() * sizeof(PairState) +
                                        k.candidates.capacity() * sizeof(BodyPair) +
                                        w.results.contacts.capacity() * sizeof(StepContact) +
                                        w.results.keys.capacity() * sizeof(PairKey));
  for (const auto& found : k.sweep.found) contacts += static_cast<double>(found.capacity() * sizeof(BodyPair));
  return {bodies / static_cast<double>(w.bodies.size()), contacts / std::max(1, w.stats.contacts)};
}

// Free fall: 1,000 grains 1.5 sizes apart in a 10 x 10 x 10 lattice, no
// walls, falling from rest and tumbling (spin ~ 10 rad/s per axis) for
// `steps` steps (no contact ever). Prints the
// cost per particle-step, the first step (start-up) excluded.
void free_fall(int threads, int steps, const std::string& export_file, const std::string& final_file,
               Real dt_scale) {
  std::vector<BlockBody> bodies;
  std::mt19937_64 rng(7);
  for (int i = 0; i < kBlockCount; ++i)
    bodies.push_back({static_cast<std::uint32_t>(i % 50), Vec3{Real(i % 10), Real(i / 10 % 10), Real(i / 100)} * (1.5 * kSize),
                      random_rotation(rng)});
  World w = bed(false, threads, bodies, 0, 0);
  std::normal_distribution<double> spin(0, 10);  // rad/s: tumbling grains, as after collisions
  for (Body& b : w.bodies)
    b.angular_momentum = rotate(b.orientation, hadamard(principal_moments(w, b), Vec3{spin(rng), spin(rng), spin(rng)}));
  const Real dt = critical_time_step(w);
  if (!export_file.empty()) {  // the same grains for bench/yade_free_fall.py: hulls, then spins (rad/s, world)
    export_bed(w, export_file, 0, 0);
    std::ofstream spins(export_file + ".spin");
    spins.precision(17);
    for (const Body& b : w.bodies) {
      const Vec3 o = angular_velocity_of(w, b);
      spins << o.x << ' ' << o.y << ' ' << o.z << '\n';
    }
    std::printf("exported %zu grains to %s (dt %.17g)\n", w.bodies.size(), export_file.c_str(), dt);
  }
  // The same span of time, the first step and `steps` more, in steps of dt * dt_scale.
  const Real h = dt * dt_scale;
  const long total = std::lround((steps + 1) / dt_scale);
  if (std::fabs(total * dt_scale - (steps + 1)) > 1e-9 * (steps + 1)) {
    std::fprintf(stderr, "--dt-scale: (steps + 1) / K must be a whole number of steps\n");
    std::exit(2);
  }
  const int first = static_cast<int>(std::max(1L, std::lround(1 / dt_scale)));
  const int timed = static_cast<int>(total - first);
  for (int i = 0; i < first; ++i) step(w, h);  // start-up: every box made, the static tree, buffers
  const auto t0 = std::chrono::steady_clock::now();
  int updates = 0;
  for (int i = 0; i < timed; ++i) {
    step(w, h);
    updates += w.stats.box_updates;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("free fall: %zu grains, %d steps of %.3g s: %.4f us per particle-step; %d contacts; "
              "%.3f box updates per particle-step (skin %.3g)\n",
              w.bodies.size(), timed, h, 1e6 * seconds / timed / static_cast<double>(w.bodies.size()),
              w.stats.contacts, static_cast<double>(updates) / timed / static_cast<double>(w.bodies.size()),
              w.settings.box_skin);
  if (!final_file.empty()) {  // each grain's hull vertices, world axes, from its centre of mass
    std::ofstream out(final_file);
    out.precision(17);
    for (const Body& b : w.bodies) {
      const Transform pose = shape_pose(w, b);
      for (const Vec3& v : std::get<Polytope>(w.templates[b.shape].shape.core).data->vertices) {
        const Vec3 x = apply(pose, v) - b.position;
        out << x.x << ' ' << x.y << ' ' << x.z << ' ';
      }
      out << '\n';
    }
  }
}

// The narrow phase alone on the contact list of the world's last step (its
// pairs of two bodies), `passes` times, each pass from the pair's warm
// start as the bed left it; the fastest pass counts.
void time_narrow_phase(const World& w, int passes) {
  std::vector<std::size_t> touching, apart;
  for (std::size_t k = 0; k < w.results.contacts.size(); ++k) {
    const StepContact& c = w.results.contacts[k];
    if (c.a_is_plane) continue;
    (c.active ? touching : apart).push_back(k);
  }
  OverlapWorkspace work;
  auto best_ns = [&](const std::vector<std::size_t>& list, bool whole) {
    double best = 1e300;
    int sink = 0;
    for (int p = 0; p < passes; ++p) {
      const auto t0 = std::chrono::steady_clock::now();
      for (const std::size_t k : list) {
        const StepContact& c = w.results.contacts[k];
        const PartPose a = part_pose(w.templates[w.bodies[c.a].shape], w.bodies[c.a], c.part_a);
        const PartPose b = part_pose(w.templates[w.bodies[c.b].shape], w.bodies[c.b], c.part_b);
        GjkCache cache = w.pairs[k].gjk;
        if (whole) sink += body_contact(*a.shape, a.pose, *b.shape, b.pose, w.settings.model, &cache, work).status ==
                           GeometryStatus::Touching;
        else sink += intersect(*a.shape, a.pose, *b.shape, b.pose, &cache);
      }
      best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    if (sink < 0) std::printf("?");
    return list.empty() ? 0.0 : 1e9 * best / static_cast<double>(list.size());
  };
  std::printf("  narrow phase, 1 thread, fastest of %d passes: %zu touching pairs of bodies, %.0f ns each "
              "(GJK's test alone %.0f ns); %zu candidates apart, %.0f ns each\n",
              passes, touching.size(), best_ns(touching, true), best_ns(touching, false), apart.size(),
              best_ns(apart, true));
}

}  // namespace

int main(int argc, char** argv) {
  bool cubes = false;
  int threads = 0, settle = 20, steps = 0, free_fall_steps = 0;
  bool narrow = false;
  std::string export_prefix, block_cache, final_file;
  Real dt_scale = 1;
  std::vector<int> counts;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--shape" && i + 1 < argc) cubes = std::strcmp(argv[++i], "cube") == 0;
    else if (a == "--threads" && i + 1 < argc) threads = std::atoi(argv[++i]);
    else if (a == "--settle" && i + 1 < argc) settle = std::atoi(argv[++i]);
    else if (a == "--steps" && i + 1 < argc) steps = std::atoi(argv[++i]);
    else if (a == "--export" && i + 1 < argc) export_prefix = argv[++i];
    else if (a == "--block" && i + 1 < argc) block_cache = argv[++i];
    else if (a == "--free-fall") free_fall_steps = 2000;
    else if (a == "--final" && i + 1 < argc) final_file = argv[++i];
    else if (a == "--dt-scale" && i + 1 < argc) dt_scale = std::atof(argv[++i]);
    else if (a == "--narrow") narrow = true;
    else if (a == "--skin" && i + 1 < argc) g_skin = std::atof(argv[++i]);
    else if (std::atoi(a.c_str()) >= kBlockCount && std::atoi(a.c_str()) % kBlockCount == 0) counts.push_back(std::atoi(a.c_str()));
    else {
      std::fprintf(stderr,
                   "usage: %s [--shape poly|cube] [--threads T] [--settle S] [--steps S] [--export PREFIX] [--block FILE]\n"
                   "          [--skin S] [--narrow] N [N ...]\n"
                   "       %s --free-fall [--threads T] [--steps S] [--skin S] [--export FILE] [--final FILE] [--dt-scale K]\n"
                   "  --skin: box skin, relative to each grain's reach (WorldSettings::box_skin)\n"
                   "  N: multiples of 1000 (default 1000 10000 100000)\n",
                   argv[0], argv[0]);
      return 2;
    }
  }
  if (free_fall_steps > 0) {
    if (!(dt_scale > 0 && dt_scale <= 1000)) {
      std::fprintf(stderr, "--dt-scale: must be > 0 and at most 1000\n");
      return 2;
    }
    free_fall(threads, steps > 0 ? steps : free_fall_steps, export_prefix, final_file, dt_scale);
    return 0;
  }
  // Under mpirun with more than one rank, the timed steps run on domains
  // (every rank builds and settles the same bed; rank 0 prints).
  const std::unique_ptr<DomainTransport> transport = mpi::launched_transport();
  const bool domains = transport && transport->size() > 1, speaks = !transport || transport->rank() == 0;
  if (domains && speaks) std::printf("domains: %d ranks\n", transport->size());
  if (counts.empty()) counts = {1000, 10000, 100000};
  const auto t_block = std::chrono::steady_clock::now();
  const std::vector<BlockBody> block = settled_block(cubes, threads, block_cache);
  if (speaks) std::printf("block: %zu %s settled in %.1f s wall\n", block.size(), cubes ? "cubes" : "polyhedra",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t_block).count());
  if (speaks) std::printf("%-8s %9s %9s %12s %14s %12s %12s %12s\n", "N", "contacts", "per_part", "ms/step", "us/part-step",
              "bytes/part", "arrays/body", "arrays/cont");
  for (const int n : counts) {
    const int tiles = n / kBlockCount;
    int tiles_x = 1;
    for (int t = 1; t * t <= tiles; ++t)
      if (tiles % t == 0) tiles_x = t;
    const int tiles_y = tiles / tiles_x;
    const long before = resident_bytes();
    World w = tiled_bed(cubes, threads, block, tiles_x, tiles_y);
    const Real dt = critical_time_step(w);
    for (int i = 0; i < settle; ++i) step(w, dt);  // the tiles' seams come to rest
    if (!export_prefix.empty())
      export_bed(w, export_prefix + std::to_string(w.bodies.size()) + ".txt", tiles_x * kBlockSide, tiles_y * kBlockSide);
    const int timed = steps > 0 ? steps : std::max(10, static_cast<int>(4e5 / n));
    const auto t0 = std::chrono::steady_clock::now();
    DomainReport report;
    if (domains) {  // the same steps on domains, outputs only at the end
      RunState run;
      run.dt = dt;
      run.steps_total = run.steps_per_output = static_cast<std::uint64_t>(timed);
      run.outputs = 1;  // as if continued: no output at the start
      run.initial_energy = kinetic_energy(w) + potential_energy(w) + w.stats.elastic_energy;
      const RunOutcome outcome = run_domains(w, run, {}, *transport, {}, {}, {}, &report);
      if (outcome.status != RunStatus::Completed && speaks) std::printf("domains: %s\n", outcome.error.c_str());
    } else {
      for (int i = 0; i < timed; ++i) step(w, dt);
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!speaks) continue;
    const long bytes = resident_bytes() - before;
    const std::size_t bodies = w.bodies.size();
    const Footprint arrays = footprint(w);
    // Contacts per particle: pair contacts count for both bodies, wall contacts for one.
    std::printf("%-8zu %9d %9.2f %12.3f %14.3f %12.0f %12.0f %12.0f\n", bodies, w.stats.contacts,
                (2.0 * w.stats.contacts - w.stats.wall_contacts) / static_cast<double>(bodies), 1e3 * seconds / timed,
                1e6 * seconds / timed / static_cast<double>(bodies), static_cast<double>(bytes) / bodies,
                arrays.per_body, arrays.per_contact);
    for (std::size_t r = 0; r < report.ranks.size(); ++r) {
      const DomainReport::Rank& d = report.ranks[r];
      std::printf("  rank %zu: %.0f bodies, %.0f ghosts, %.2f moved out and %.1f kB sent per step; per step %.2f ms "
                  "in its stages, %.2f ms exchanging, %.2f ms in all (%.3f us per particle-step, outputs aside)\n",
                  r, d.owned, d.ghosts, d.moved_out, d.bytes_sent / 1e3, 1e3 * d.step_seconds, 1e3 * d.exchange_seconds,
                  1e3 * d.loop_seconds, 1e6 * d.loop_seconds / static_cast<double>(bodies));
    }
    if (narrow && !domains) time_narrow_phase(w, 20);
    std::fflush(stdout);
  }
  return 0;
}
