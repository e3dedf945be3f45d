#include "gjkdem/dem/measure.hpp"

#include <cmath>
#include <span>
#include <stdexcept>
#include <utility>
#include <vector>

#include "gjkdem/dem/periodic.hpp"
#include "gjkdem/math/polygon_clip.hpp"
#include "gjkdem/shape/tessellate.hpp"

namespace gjkdem::dem {

namespace {

bool inside(const MeasureRegion& r, const Vec3& p) noexcept {
  if (r.round) return ball_inside(*r.round, p, 0);
  return p.x >= r.lo.x && p.x <= r.hi.x && p.y >= r.lo.y && p.y <= r.hi.y && p.z >= r.lo.z && p.z <= r.hi.z;
}

/// Distance from p to the region (0 inside).
Real distance_to(const MeasureRegion& r, const Vec3& p) noexcept {
  if (r.round) return distance_to(*r.round, p);
  const Vec3 d{std::fmax(std::fmax(r.lo.x - p.x, p.x - r.hi.x), 0.0), std::fmax(std::fmax(r.lo.y - p.y, p.y - r.hi.y), 0.0),
               std::fmax(std::fmax(r.lo.z - p.z, p.z - r.hi.z), 0.0)};
  return length(d);
}

/// Distance from p to the region's boundary, p inside.
Real depth_in(const MeasureRegion& r, const Vec3& p) noexcept {
  if (r.round) return depth_in(*r.round, p);
  return std::fmin(std::fmin(std::fmin(p.x - r.lo.x, r.hi.x - p.x), std::fmin(p.y - r.lo.y, r.hi.y - p.y)),
                   std::fmin(p.z - r.lo.z, r.hi.z - p.z));
}

/// Shapes overlap() clips exactly (contact/overlap.hpp); the others are
/// clipped as tessellations.
bool clipped_exactly(const Shape& s) noexcept {
  return s.margin == 0 && (std::holds_alternative<Polytope>(s.core) || std::holds_alternative<Box>(s.core) ||
                           std::holds_alternative<Triangle>(s.core));
}

// The area of triangle abc inside the planes (Sutherland-Hodgman).
Real area_inside(const Vec3& a, const Vec3& b, const Vec3& c, std::span<const OverlapWorkspace::Plane> planes,
                 std::vector<Vec3>& poly, std::vector<Vec3>& next) {
  poly.assign({a, b, c});
  for (const auto& [n, d] : planes) {
    clip_polygon(poly, [&](const Vec3& p) { return dot(n, p) - d; }, next);
    poly.swap(next);
    if (poly.empty()) return 0;
  }
  Vec3 twice;
  for (std::size_t i = 1; i + 1 < poly.size(); ++i) twice += cross(poly[i] - poly[0], poly[i + 1] - poly[0]);
  return 0.5 * length(twice);
}

void add_outer(Mat3& m, const Vec3& a, const Vec3& b) noexcept {
  for (int i = 0; i < 3; ++i) m.row[i] += b * a[i];
}

}  // namespace

std::vector<MeasuredContact> touching_contacts(const World& w) {
  std::vector<MeasuredContact> out;
  for (const StepContact& c : w.results.contacts)
    if (c.active) out.push_back({c.a, c.a_is_plane, c.b, c.geometry.point, c.geometry.normal, c.force});
  return out;
}

std::optional<MeasureRegion> moving_bodies_box(const World& w) {
  MeasureRegion box{Vec3{1, 1, 1} * INFINITY, Vec3{1, 1, 1} * -INFINITY};
  bool any = false;
  for (const Body& b : w.bodies) {
    if (b.fixed) continue;
    const Real reach = w.templates[b.shape].reach;
    box.lo = min(box.lo, b.position - Vec3{reach, reach, reach});
    box.hi = max(box.hi, b.position + Vec3{reach, reach, reach});
    any = true;
  }
  if (!any) return std::nullopt;
  return box;
}

Real volume_inside(const World& w, const Body& b, const MeasureRegion& region, MeasureWorkspace& work) {
  const ShapeTemplate& t = w.templates[b.shape];
  if (distance_to(region, b.position) >= t.reach) return 0;
  if (inside(region, b.position) && depth_in(region, b.position) >= t.reach) return t.unit_mass.volume;
  if (work.region_for != region) {
    if (region.round) {
      work.region_solid = Shape{tessellate(round_shape(*region.round), kMeasureTessellation).polytope};
      work.region_pose = round_pose(*region.round);
    } else {
      const Vec3 half = (region.hi - region.lo) * 0.5;
      work.region_solid = Shape{Box{half}};
      work.region_pose = Transform::from(region.lo + half, Quat{});
    }
    work.region_surface.reset();
    work.region_for = region;
  }
  const Shape& clip = work.region_solid;
  const Transform& clip_pose = work.region_pose;
  if (t.shell) {  // its plates: each triangle's area inside, times the thickness
    if (!face_planes_near(clip, clip_pose, b.position, t.reach, work.planes)) return 0;
    const Transform pose = shape_pose(t, b);
    const Shell& s = *t.shell;
    Real area = 0;
    for (const TriangleIndices& tri : s.triangles)
      area += area_inside(apply(pose, s.vertices[tri[0]]), apply(pose, s.vertices[tri[1]]), apply(pose, s.vertices[tri[2]]),
                          work.planes, work.polygon, work.clipped_polygon);
    return area * 2 * s.margin;
  }
  const std::uint32_t parts = t.parts.empty() ? 1 : static_cast<std::uint32_t>(t.parts.size());
  Real volume = 0;
  for (std::uint32_t k = 0; k < parts; ++k) {
    const PartPose part = part_pose(t, b, k);
    if (surface_side(t, k)) {  // its own surface, not its hull: A ∩ region exactly, in the part's frame
      if (!work.region_surface) {
        work.region_surface = region.round ? polytope_surface(std::get<Polytope>(clip.core))
                                           : box_surface(std::get<Box>(clip.core));
        work.placed = *work.region_surface;
      }
      repose(*work.region_surface, relative(part.pose, clip_pose), work.placed);
      volume += surface_overlap(work.placed, *surface_of(t, k), work.surface_overlap).volume;
      continue;
    }
    const Real part_volume = t.parts.empty() ? t.unit_mass.volume : t.parts[k].volume;
    // The part as clipped: its shape, or a tessellation when it is curved
    // (clipping has no closed form for it), and that solid's own volume.
    const std::uint64_t key = std::uint64_t{b.shape} << 32 | k;
    auto found = work.clipped.find(key);
    if (found == work.clipped.end()) {
      MeasureWorkspace::ClippedShape c;
      c.tessellated = !clipped_exactly(*part.shape);
      if (c.tessellated) c.tessellation = Shape{tessellate(*part.shape, kMeasureTessellation).polytope};
      c.volume = mass_properties(c.tessellated ? c.tessellation : *part.shape).volume;
      found = work.clipped.emplace(key, std::move(c)).first;
    }
    const MeasureWorkspace::ClippedShape& c = found->second;
    const Shape& solid = c.tessellated ? c.tessellation : *part.shape;
    volume += overlap(clip, clip_pose, solid, part.pose, work.overlap).volume / c.volume * part_volume;
  }
  return volume;
}

Measures measure(const World& w, std::span<const MeasuredContact> contacts, const MeasureRegion& region,
                 MeasureWorkspace& work) {
  Measures m;
  m.region_volume = region.volume();
  if (region.round) {
    const RoundRegion& g = *region.round;
    if (!is_finite(g.base) || !is_finite(g.axis) || !(length(g.axis) > 0) || !(g.radius > 0) ||
        !std::isfinite(m.region_volume) || (g.kind == RoundRegion::Kind::Cylinder && !(g.height > 0)))
      throw std::invalid_argument("the measurement region's base and axis must be finite, the axis not zero, its "
                                  "radius (and a cylinder's height) finite and > 0");
  } else if (!(region.lo.x < region.hi.x && region.lo.y < region.hi.y && region.lo.z < region.hi.z) ||
             !std::isfinite(m.region_volume)) {
    throw std::invalid_argument("the measurement region must have lo < hi on every axis, all finite");
  }
  // Fractions and stresses divide by it: a volume that underflows (a region
  // of 1e-120 m sides) would turn every measure into inf or nan.
  if (!std::isnormal(m.region_volume))
    throw std::invalid_argument("the measurement region's volume underflows double precision: make it larger");
  std::vector<char> counted(w.bodies.size(), 0);
  // In a periodic world the region also holds the images of the bodies near
  // the cell's faces (a body straddling one fills both sides).
  const std::vector<Vec3> shifts = image_shifts(w.cell.now);
  for (std::size_t k = 0; k < w.bodies.size(); ++k) {
    const Body& b = w.bodies[k];
    if (b.fixed) continue;
    for (const Vec3& shift : shifts) {
      Body image = b;
      image.position += shift;
      m.solid_volume += volume_inside(w, image, region, work);
    }
    if (inside(region, b.position)) counted[k] = 1, ++m.grains;
  }
  m.solid_fraction = m.solid_volume / m.region_volume;

  std::size_t ends = 0;  // contact ends on counted grains
  Mat3 sum{{Vec3{}, Vec3{}, Vec3{}}};
  for (const MeasuredContact& c : contacts) {
    const bool first = !c.first_is_plane && counted[c.first], second = counted[c.second] != 0;
    if (!first && !second) continue;
    ++m.contacts;
    m.normal_forces.push_back(std::fabs(dot(c.force, c.normal)));
    if (second) add_outer(sum, nearest_image(w.cell.now, c.point - w.bodies[c.second].position), c.force), ++ends;
    if (first) add_outer(sum, nearest_image(w.cell.now, c.point - w.bodies[c.first].position), -c.force), ++ends;
  }
  m.coordination = m.grains ? static_cast<Real>(ends) / static_cast<Real>(m.grains) : 0;
  for (const Real f : m.normal_forces) m.mean_normal_force += f;
  if (m.contacts) m.mean_normal_force /= static_cast<Real>(m.contacts);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m.stress.row[i][j] = -0.5 * (sum.row[i][j] + sum.row[j][i]) / m.region_volume;
  m.pressure = (m.stress.row[0].x + m.stress.row[1].y + m.stress.row[2].z) / 3;
  return m;
}

}  // namespace gjkdem::dem
