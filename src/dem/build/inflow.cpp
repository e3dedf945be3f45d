#include "gjkdem/dem/inflow.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "gjkdem/collide/query.hpp"
#include "gjkdem/dem/surface_contact.hpp"
#include "gjkdem/dem/world.hpp"

namespace gjkdem::dem {
namespace {

std::uint64_t mix(std::uint64_t x) noexcept {  // splitmix64's finaliser
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// Draw k of the placement try `attempt` of body n.
enum Draw : std::uint64_t { kVariant = 0, kX, kY, kZ, kTurn1, kTurn2, kTurn3 };

// A uniformly random rotation from three uniform numbers (Shoemake 1992).
Quat uniform_rotation(Real u1, Real u2, Real u3) noexcept {
  const Real a = std::sqrt(1 - u1), b = std::sqrt(u1);
  const Real t2 = 2 * kPi * u2, t3 = 2 * kPi * u3;
  return normalized(Quat{b * std::cos(t3), a * std::sin(t2), a * std::cos(t2), b * std::sin(t3)});
}

// The bodies (or their periodic images) that might touch a body placed in
// the inflow's region.
std::vector<std::uint32_t> bodies_near(std::span<const Body> bodies, const Makeup& makeup, const Inflow& f,
                                       const std::vector<Vec3>& shifts) {
  std::vector<std::uint32_t> near;
  for (std::uint32_t i = 0; i < bodies.size(); ++i)
    for (const Vec3& s : shifts)
      if (near_inflow(makeup.templates, f, bodies[i], s)) {
        near.push_back(i);
        break;
      }
  return near;
}

// Whether the next body of inflow f (in state s) is due at `time`.
bool due(const Inflow& f, const InflowState& s, const Makeup& makeup, Real time) {
  if (time < f.start || (f.count > 0 && s.inserted >= f.count)) return false;
  const Real elapsed = std::fmin(time, f.stop) - f.start;
  const Real mass = makeup.mass(f.templates[inflow_variant(f, s.inserted)], f.material);
  return f.rate > 0 ? static_cast<Real>(s.inserted) <= f.rate * elapsed : s.mass + 0.5 * mass <= f.mass_rate * elapsed;
}

bool is_free(std::span<const Body> bodies, const InflowSite& site, const std::vector<std::uint32_t>& near,
             const std::vector<Vec3>& shifts, const ShapeTemplate& t, const Body& body,
             std::optional<SurfaceScratch>& scratch, std::vector<SurfacePatchContact>& patches) {
  for (const PlaneWall& p : site.planes)
    if (dot(body.position - p.point, p.normal) < t.reach) return false;
  const Transform pose = shape_pose(t, body);
  for (const std::uint32_t i : near) {
    const Body& other = bodies[i];
    const ShapeTemplate& o = site.makeup.templates[other.shape];
    for (const Vec3& s : shifts) {
      if (!(length(other.position + s - body.position) < o.reach + t.reach)) continue;
      Transform other_pose = shape_pose(o, other);
      other_pose.translation += s;
      if (!intersect(t.shape, pose, o.shape, other_pose)) continue;
      // By other's solid, not its hull (an inserted compound by its hull: a
      // bound). The scratch is made once a hull is in the way: most steps
      // insert nothing.
      if (!scratch) scratch.emplace();
      if (placed_body_meets(t.shape, pose, t.surface, t.surface_grain, o, other_pose, *scratch, patches)) return false;
    }
  }
  return true;
}

}  // namespace

InflowSite inflow_site(const World& w) {
  return {{w.templates, w.materials}, w.planes, w.cell.now, w.time, w.settings.gravity};
}

bool near_inflow(std::span<const ShapeTemplate> templates, const Inflow& f, const Body& b, const Vec3& shift) noexcept {
  Real reach = 0;
  for (const std::uint32_t t : f.templates) reach = std::fmax(reach, templates[t].reach);
  const Vec3 image = b.position + shift;
  const Vec3 closest = max(f.lo, min(f.hi, image));  // of the region, to the body
  return length(image - closest) < templates[b.shape].reach + reach;
}

bool inflows_due(std::span<const Inflow> inflows, std::span<const InflowState> states, const Makeup& makeup,
                 Real time) {
  for (std::size_t k = 0; k < inflows.size(); ++k)
    if (due(inflows[k], states[k], makeup, time)) return true;
  return false;
}

Real keyed_uniform(std::uint64_t seed, std::uint64_t a, std::uint64_t b, std::uint64_t c) noexcept {
  const std::uint64_t h = mix(mix(mix(mix(seed) ^ a) ^ b) ^ c);
  return static_cast<Real>(h >> 11) * 0x1.0p-53;
}

std::uint32_t inflow_variant(const Inflow& f, std::uint64_t n) noexcept {
  const Real u = keyed_uniform(f.seed, n, 0, kVariant);
  const auto it = std::upper_bound(f.cumulative.begin(), f.cumulative.end(), u);
  return static_cast<std::uint32_t>(std::min<std::size_t>(it - f.cumulative.begin(), f.cumulative.size() - 1));
}

std::uint64_t inflow_capacity(const Inflow& f, const Makeup& makeup) noexcept {
  Real lightest_mass = std::numeric_limits<Real>::infinity();
  for (const std::uint32_t t : f.templates)
    lightest_mass = std::fmin(lightest_mass, makeup.mass(t, f.material));
  Real most = std::numeric_limits<Real>::infinity();
  if (f.count > 0) most = static_cast<Real>(f.count);
  const Real span = f.stop - f.start;
  if (f.rate > 0) most = std::fmin(most, std::floor(f.rate * span) + 1);
  else if (lightest_mass > 0) most = std::fmin(most, std::floor(f.mass_rate * span / lightest_mass + 0.5) + 1);
  return most < 1.8e19 ? static_cast<std::uint64_t>(most) : std::numeric_limits<std::uint64_t>::max();
}

std::size_t run_inflows(std::span<const Inflow> inflows, std::span<InflowState> states, const InflowSite& site,
                        std::vector<Body>& bodies, std::uint64_t next_id) {
  const Makeup& makeup = site.makeup;
  std::size_t added = 0;
  std::optional<SurfaceScratch> scratch;
  std::vector<SurfacePatchContact> patches;
  for (std::size_t k = 0; k < inflows.size(); ++k) {
    const Inflow& f = inflows[k];
    InflowState& s = states[k];
    std::vector<std::uint32_t> near;
    std::vector<Vec3> shifts;  // made once a body is due: most steps insert nothing
    bool looked = false;
    while (due(f, s, makeup, site.time)) {
      const std::uint32_t v = inflow_variant(f, s.inserted);
      const ShapeTemplate& t = makeup.templates[f.templates[v]];
      const Real mass = makeup.mass(f.templates[v], f.material);
      if (!looked) {
        shifts = image_shifts(site.cell);
        near = bodies_near(bodies, makeup, f, shifts);
        looked = true;
      }
      Body body;
      body.shape = f.templates[v];
      body.material = f.material;
      body.velocity = f.velocity;
      bool placed = false;
      for (int a = 0; a < kInflowAttemptsPerStep && !placed; ++a) {
        const std::uint64_t attempt = s.attempts++;
        const auto u = [&](Draw d) { return keyed_uniform(f.seed, s.inserted, attempt, d); };
        body.position = f.round ? round_point(*f.round, u(kX), u(kY), u(kZ))
                                : f.lo + hadamard(f.hi - f.lo, {u(kX), u(kY), u(kZ)});
        body.orientation = uniform_rotation(u(kTurn1), u(kTurn2), u(kTurn3));
        placed = is_free(bodies, site, near, shifts, t, body, scratch, patches);
      }
      if (!placed) {
        ++s.behind;
        break;
      }
      body.id = next_id++;
      bodies.push_back(body);
      near.push_back(static_cast<std::uint32_t>(bodies.size() - 1));
      ++s.inserted;
      s.mass += mass;
      s.energy += mass * (0.5 * dot(body.velocity, body.velocity) - dot(site.gravity, body.position));
      ++added;
    }
  }
  return added;
}

}  // namespace gjkdem::dem
