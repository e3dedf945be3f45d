#include "gjkdem/dem/narrow_phase.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include "gjkdem/collide/query.hpp"
#include "gjkdem/contact/manifold.hpp"
#include "gjkdem/contact/half_space.hpp"
#include "gjkdem/tolerances.hpp"

namespace gjkdem::dem {

ContactGeometry plane_contact(const PlaneWall& wall, const Shape& sb, const Transform& pb, ContactModel model) {
  ContactGeometry c;
  const HalfSpaceContact h = half_space_contact(sb, pb, wall.point, wall.normal);
  if (!h.touching) return c;
  c.normal = wall.normal;
  if (model == ContactModel::Volume) {
    if (!h.has_volume) {
      c.status = GeometryStatus::Unsupported;
      return c;
    }
    if (!(h.volume > 0)) return c;
    if (!(h.area > 0)) {  // no face cut: wholly beyond (went through), or a vertex grazing the plane
      const Vec3 top = apply(pb, support(sb, apply_inverse_rotation(pb, wall.normal)));
      if (dot(top - wall.point, wall.normal) < 0) c.status = GeometryStatus::Through;
      return c;
    }
    c.area = h.area;
    c.volume = h.volume;
    c.depth = h.volume / h.area;
    c.depth_integral = h.depth_integral;
    // On the wall, below the centroid of the part under it (half_space.hpp).
    c.point = h.centroid + wall.normal * dot(wall.point - h.centroid, wall.normal);
  } else {
    if (!(h.depth > 0)) return c;
    c.depth = h.depth;
    // A flat face on the wall pushes at its middle, not at one corner.
    c.point = h.has_volume && h.area > 0 ? h.face_centroid : h.deepest + wall.normal * (h.depth / 2);
  }
  c.moment = cross(c.point, c.normal);
  c.status = GeometryStatus::Touching;
  return c;
}

ContactGeometry body_contact(const Shape& sa, const Transform& pa, const Shape& sb, const Transform& pb,
                             ContactModel model, GjkCache* cache, OverlapWorkspace& work) {
  ContactGeometry c;
  if (model == ContactModel::Volume) {
    const OverlapResult o = overlap(sa, pa, sb, pb, work, cache);
    if (o.status == OverlapStatus::Unsupported) {
      c.status = GeometryStatus::Unsupported;
      return c;
    }
    if (o.status != OverlapStatus::Overlapping || !o.has_normal) return c;
    c.area = length(o.area_a);
    if (!(c.area > 0)) return c;
    c.normal = o.area_a / c.area;
    c.volume = o.volume;
    // Feng's line of action, level with the centroid; the moment carries the
    // twisting couple: about the origin it is (F / |S_A|) M_A.
    c.point = o.application_point + c.normal * dot(o.centroid - o.application_point, c.normal);
    c.depth = o.volume / c.area;
    c.moment = o.moment_a / c.area;
  } else {
    const PenetrationResult r = penetration(sa, pa, sb, pb, cache);
    if (!r.intersect || !(r.depth > 0)) return c;
    c.normal = r.normal;
    c.depth = r.depth;
    c.point = (r.witness_a + r.witness_b) * 0.5;
    c.moment = cross(c.point, c.normal);
  }
  c.status = GeometryStatus::Touching;
  return c;
}

namespace {

struct WallKey {  // a moving body's part against one wall group
  std::uint32_t body, part, group;
  std::size_t index;
};

// A body near a seam of a mesh wall touches the neighbouring piece's edge
// too, with a tilted normal and less depth: inside that piece's edge or
// corner region. Such a contact beside a deeper contact in a piece's face
// region (within the body's radius) is the same touch: it is dropped.
void drop_seam_echoes(std::span<const Body> bodies, std::span<const ShapeTemplate> templates,
                      std::vector<StepContact>& contacts, std::span<const WallKey> run) {
  const auto in_face_region = [&](const StepContact& c, std::uint32_t body) {
    const Body& piece = bodies[c.a == body ? c.b : c.a];
    const ShapeTemplate& t = templates[piece.shape];
    if (!t.wall_face) return true;  // not a mesh wall's piece: no regions
    const Triangle& f = *t.wall_face;
    const Vec3 n = apply_rotation(shape_pose(t, piece), normalized(cross(f.v[1] - f.v[0], f.v[2] - f.v[0])));
    return std::fabs(dot(n, c.geometry.normal)) >= kWallFaceRegionCos;
  };
  const Real reach = templates[bodies[run[0].body].shape].curvature_radius;
  for (const WallKey& k : run) {
    StepContact& c = contacts[k.index];
    if (in_face_region(c, k.body)) continue;
    for (const WallKey& other : run) {
      const StepContact& o = contacts[other.index];
      if (other.index != k.index && o.active && o.geometry.depth > c.geometry.depth &&
          length(o.geometry.point - c.geometry.point) <= reach && in_face_region(o, other.body)) {
        c.active = false;
        break;
      }
    }
  }
}

}  // namespace

void merge_wall_contacts(std::span<const Body> bodies, std::span<const ShapeTemplate> templates,
                         std::vector<StepContact>& contacts) {
  using Key = WallKey;
  std::vector<Key> keys;
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const StepContact& c = contacts[k];
    if (!c.active || c.a_is_plane || c.surface) continue;  // a surface grain's patches are separate contacts
    const Body& a = bodies[c.a];
    const Body& b = bodies[c.b];
    if (a.group > 0 && !b.fixed) keys.push_back({c.b, c.part_b, a.group, k});
    else if (b.group > 0 && !a.fixed) keys.push_back({c.a, c.part_a, b.group, k});
  }
  if (keys.empty()) return;
  std::stable_sort(keys.begin(), keys.end(), [](const Key& x, const Key& y) {
    return std::tuple(x.body, x.part, x.group) < std::tuple(y.body, y.part, y.group);
  });
  std::vector<ContactPoint> points;
  std::vector<int> cluster_of;
  for (std::size_t begin = 0; begin < keys.size();) {
    std::size_t end = begin + 1;
    while (end < keys.size() && keys[end].body == keys[begin].body && keys[end].part == keys[begin].part &&
           keys[end].group == keys[begin].group)
      ++end;
    const std::size_t run_end = end;
    if (end - begin > 1) {
      drop_seam_echoes(bodies, templates, contacts, std::span(keys).subspan(begin, end - begin));
      end = std::stable_partition(keys.begin() + begin, keys.begin() + end,
                                  [&](const Key& k) { return contacts[k.index].active; }) -
            keys.begin();
    }
    if (end - begin > 1) {
      points.clear();
      for (std::size_t k = begin; k < end; ++k) {
        const StepContact& c = contacts[keys[k].index];
        const bool wall_is_a = c.b == keys[k].body;
        const ContactGeometry& g = c.geometry;
        points.push_back({g.point, wall_is_a ? g.normal : -g.normal, g.depth});  // normals wall -> body
      }
      const Real size = templates[bodies[keys[begin].body].shape].curvature_radius;
      const std::vector<ContactPoint> merged = cluster_contacts(points, size, kWallMergeCos, &cluster_of);
      for (std::size_t m = 0; m < merged.size(); ++m) {
        std::size_t carrier = 0;  // the deepest member carries the cluster (and its springs)
        Real deepest = -std::numeric_limits<Real>::infinity();
        for (std::size_t k = begin; k < end; ++k)
          if (cluster_of[k - begin] == static_cast<int>(m) && contacts[keys[k].index].geometry.depth > deepest) {
            deepest = contacts[keys[k].index].geometry.depth;
            carrier = keys[k].index;
          }
        for (std::size_t k = begin; k < end; ++k)
          if (cluster_of[k - begin] == static_cast<int>(m) && keys[k].index != carrier)
            contacts[keys[k].index].active = false;
        StepContact& c = contacts[carrier];
        const bool wall_is_a = c.b == keys[begin].body;
        c.geometry.point = merged[m].point;
        c.geometry.depth = merged[m].depth;
        c.geometry.normal = wall_is_a ? merged[m].normal : -merged[m].normal;
        c.geometry.moment = cross(c.geometry.point, c.geometry.normal);
      }
    }
    begin = run_end;
  }
}

}  // namespace gjkdem::dem
