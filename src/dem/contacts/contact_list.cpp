// The contact list of a force evaluation (stages.hpp).
#include <algorithm>
#include <cstdint>
#include <vector>

#include "step/stages.hpp"

namespace gjkdem::dem::detail {
namespace {

// A sphere about each part of a body, world frame (one for a convex body).
struct PartSphere {
  Vec3 centre;
  Real radius;
};

void part_spheres(const ShapeTemplate& t, const Body& b, std::vector<PartSphere>& out, const Vec3& shift = {}) {
  out.clear();
  Transform pose = shape_pose(t, b);
  pose.translation += shift;
  if (t.parts.empty()) {
    out.push_back({pose.translation, bounding_radius(t.shape)});
    return;
  }
  for (const TemplatePart& p : t.parts) out.push_back({apply(pose, p.pose.translation), p.radius});
}

}  // namespace

// The contact list in pair-key order (bodies are in increasing id order and
// plane ids lie above every body's): for each body, its candidates with
// larger indices, then the plane walls its box reaches; for compounds, each
// pair of parts whose bounding spheres meet, in part order.
void list_contacts(std::span<const Body> bodies, std::span<const ShapeTemplate> templates,
                   std::span<const PlaneWall> planes, std::span<const Aabb> boxes, const PeriodicCell& cell,
                   const DomainRole* domain, const StepWorkspace& work, StepResults& results) {
  std::vector<StepContact>& contacts = results.contacts;
  contacts.clear();
  results.keys.clear();
  const std::vector<BodyPair>& pairs = work.candidates;
  std::vector<PartSphere> parts_a, parts_b;
  // Worlds without compounds never look at templates here.
  const bool any_compound =
      std::any_of(templates.begin(), templates.end(), [](const ShapeTemplate& t) { return !t.parts.empty(); });
  std::size_t k = 0;
  for (std::uint32_t i = 0; i < bodies.size(); ++i) {
    const Body& body = bodies[i];
    const ShapeTemplate& t = templates[body.shape];
    const bool compound = any_compound && !t.parts.empty();
    if (compound) part_spheres(t, body, parts_a);
    for (; k < pairs.size() && pairs[k].first == i; ++k) {
      if (domain && !domain->owns(i) && !domain->owns(pairs[k].second)) continue;  // another domain's pair
      const Body& other = bodies[pairs[k].second];
      const std::uint8_t image = work.candidate_images.empty() ? kNoImage : work.candidate_images[k];
      if (!any_compound || (!compound && templates[other.shape].parts.empty())) {
        StepContact& c = contacts.emplace_back();  // made in place: a contact is large
        c.a = i;
        c.b = pairs[k].second;
        c.image = image;
        results.keys.push_back(pair_key(body.id, other.id));
        continue;
      }
      StepContact c;
      c.a = i;
      c.b = pairs[k].second;
      c.image = image;
      if (!compound) part_spheres(t, body, parts_a);
      part_spheres(templates[other.shape], other, parts_b, image_shift_of(cell, c));
      for (std::uint16_t pa = 0; pa < parts_a.size(); ++pa)
        for (std::uint16_t pb = 0; pb < parts_b.size(); ++pb) {
          if (length(parts_a[pa].centre - parts_b[pb].centre) > parts_a[pa].radius + parts_b[pb].radius) continue;
          c.part_a = pa, c.part_b = pb;
          contacts.push_back(c);
          results.keys.push_back(pair_key(body.id, other.id, pa, pb));
        }
    }
    if (body.fixed || (domain && !domain->owns(i))) continue;
    const Aabb& box = boxes[i];
    for (std::uint32_t p = 0; p < planes.size(); ++p) {
      const PlaneWall& wall = planes[p];
      Real lowest = -dot(wall.normal, wall.point);  // of the box's corners above the plane
      for (int axis = 0; axis < 3; ++axis) lowest += wall.normal[axis] * (wall.normal[axis] > 0 ? box.lo[axis] : box.hi[axis]);
      if (lowest > 0) continue;
      if (!compound) {
        StepContact& c = contacts.emplace_back();
        c.a = p;
        c.b = i;
        c.a_is_plane = true;
        results.keys.push_back(pair_key(body.id, wall.id));
        continue;
      }
      StepContact c;
      c.a = p;
      c.b = i;
      c.a_is_plane = true;
      for (std::uint16_t pb = 0; pb < parts_a.size(); ++pb) {
        if (dot(parts_a[pb].centre - wall.point, wall.normal) > parts_a[pb].radius) continue;
        c.part_b = pb;
        contacts.push_back(c);
        results.keys.push_back(pair_key(body.id, wall.id, pb, 0));
      }
    }
  }
}

}  // namespace gjkdem::dem::detail
