// The contacts of surface grains: one per patch (stages.hpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>

#include "gjkdem/collide/query.hpp"
#include "parallel.hpp"
#include "step/stages.hpp"
#include "gjkdem/dem/pair_state.hpp"
#include "gjkdem/tolerances.hpp"

namespace gjkdem::dem::detail {
namespace {

// The route of a listed contact (body.hpp's pair_route and plane_route):
// all but Convex are found here, by patches.
ContactRoute route_of(std::span<const Body> bodies, std::span<const ShapeTemplate> templates, const StepContact& c) {
  const PartKind b = part_kind(templates[bodies[c.b].shape], c.part_b);
  if (c.a_is_plane) return plane_route(b);
  return pair_route(part_kind(templates[bodies[c.a].shape], c.part_a), b);
}

// The patches of one listed contact of the Patches or Shell route (Margin
// contacts are found by find_margin_patches), or why there are none to find.
GeometryStatus find_patches(std::span<const Body> bodies, std::span<const ShapeTemplate> templates,
                            std::span<const PlaneWall> planes, const PeriodicCell& cell, const StepContact& c,
                            SurfaceScratch& scratch, std::vector<SurfacePatchContact>& out) {
  out.clear();
  const ContactRoute route = route_of(bodies, templates, c);
  // A compound meets a surface part by part, as it meets other bodies.
  const Body& b = bodies[c.b];
  const ShapeTemplate& tb = templates[b.shape];
  PartPose pb = part_pose(tb, b, c.part_b);
  pb.pose.translation += image_shift_of(cell, c);
  const std::shared_ptr<const Surface>& sb = surface_of(tb, c.part_b);
  if (c.a_is_plane && route == ContactRoute::Shell)
    return plane_shell_patches(planes[c.a], *tb.shell, pb.pose, scratch, out) ? GeometryStatus::Touching
                                                                               : GeometryStatus::Through;
  if (c.a_is_plane && !sb) return GeometryStatus::Unsupported;
  if (c.a_is_plane)
    return plane_surface_patches(planes[c.a], *sb, pb.pose, scratch, out) ? GeometryStatus::Touching
                                                                                : GeometryStatus::Through;
  const Body& a = bodies[c.a];
  const ShapeTemplate& ta = templates[a.shape];
  const PartPose pa = part_pose(ta, a, c.part_a);
  if (route == ContactRoute::Shell)
    return ta.shell ? shell_patches(ta, pa.pose, tb, c.part_b, pb, true, scratch, out)
                    : shell_patches(tb, pb.pose, ta, c.part_a, pa, false, scratch, out);
  const std::shared_ptr<const Surface>& sa = surface_of(ta, c.part_a);
  // Hulls apart (GJK on the convex shapes that hold the surfaces): no
  // patch, and nothing to move or traverse.
  if (!intersect(*pa.shape, pa.pose, *pb.shape, pb.pose)) return GeometryStatus::Touching;
  if (!sa || !sb) return GeometryStatus::Unsupported;
  return surface_patches(sa, pa.pose, sb, pb.pose, scratch, out);
}

// A contact of the Margin route, a grain and a mesh wall's piece: the
// grain's index (the other is the piece); kNotMargin for other routes.
constexpr std::uint32_t kNotMargin = ~0u;
std::uint32_t margin_grain(std::span<const Body> bodies, std::span<const ShapeTemplate> templates,
                           const StepContact& c) {
  if (route_of(bodies, templates, c) != ContactRoute::Margin) return kNotMargin;
  return part_kind(templates[bodies[c.a].shape], c.part_a) == PartKind::WallPiece ? c.b : c.a;
}

// The patches of a grain's contacts with the pieces of one mesh wall
// (`members`: positions in `listed`), found at once so that a patch over a
// seam is one contact: each goes to the member whose piece its deepest pair
// touches.
void find_margin_patches(std::span<const Body> bodies, std::span<const ShapeTemplate> templates,
                         const PeriodicCell& cell, std::span<const StepContact> contacts,
                         std::span<const std::uint32_t> listed, std::span<const std::uint32_t> members,
                         SurfaceScratch& scratch, std::span<std::vector<SurfacePatchContact>> found,
                         std::span<GeometryStatus> status) {
  const StepContact& first = contacts[listed[members[0]]];
  const std::uint32_t g = margin_grain(bodies, templates, first);
  const bool grain_is_b = g == first.b;
  const Body& grain = bodies[g];
  const ShapeTemplate& tg = templates[grain.shape];
  const std::uint32_t part = grain_is_b ? first.part_b : first.part_a;  // a compound's surface part
  // Periodic worlds: each contact has b at its image, the grain or a piece.
  // The grain stays where it is and each piece moves to where it meets it,
  // so the pieces met across the cell's face are one surface with the others
  // (one patch over that seam too); a patch found with a piece whose
  // contact has the grain at an image is moved there.
  const Transform pose = part_pose(tg, grain, part).pose;
  scratch.margin_pieces.clear();
  for (const std::uint32_t m : members) {
    const StepContact& c = contacts[listed[m]];
    const Body& piece = bodies[grain_is_b ? c.a : c.b];
    const ShapeTemplate& tp = templates[piece.shape];
    Transform at = shape_pose(tp, piece);
    const Vec3 image = image_shift_of(cell, c);
    at.translation += grain_is_b ? -image : image;
    scratch.margin_pieces.push_back(placed_margin_triangle(tp, at));
    found[m].clear();
    status[m] = GeometryStatus::Touching;
  }
  margin_patches(margin_triangles(tg, part), pose, scratch.margin_pieces, scratch, scratch.margin_found,
                 scratch.margin_hosts);
  for (std::size_t k = 0; k < scratch.margin_found.size(); ++k) {
    SurfacePatchContact p = scratch.margin_found[k];
    const std::uint32_t host = members[scratch.margin_hosts[k]];
    if (grain_is_b) {
      const Vec3 image = image_shift_of(cell, contacts[listed[host]]);
      p.geometry.point += image, p.centroid += image;
    } else {
      p.geometry.normal = -p.geometry.normal;  // a -> b
    }
    p.geometry.moment = cross(p.geometry.point, p.geometry.normal);
    found[host].push_back(p);
  }
}

// A patch's key is its pair's with the parts field holding the parts it
// touches and its slot: `prefix | slot`, the slot within `slot_mask`.
// Where at most one side is a compound, its part (0 for none) in the high
// half and the slot in the low: patches of one part follow each other,
// parts in order, as the list is sorted. Where both are, a flag bit above
// the pair key's parts (10 bits each: kMaxCompoundParts), the two parts and
// an 11-bit slot: those keys follow the pair's other contacts' keys.
struct PatchKeys {
  std::uint32_t prefix, slot_mask;
};
static_assert(kMaxCompoundParts <= 1024, "two compounds' patch keys hold 10 bits a part");
PatchKeys patch_keys_of(const PairKey& key, bool two_compounds) {
  const std::uint32_t lo = key.parts >> 16, hi = key.parts & 0xffffu;  // pair_key's parts
  if (!two_compounds) return {(lo + hi) << 16, 0xffffu};
  return {1u << 31 | lo << 21 | hi << 11, 0x7ffu};
}

// How far a patch may have moved and still be the same: kPatchMatchRel of
// the smaller moving body's equivalent radius.
Real match_reach(std::span<const Body> bodies, std::span<const ShapeTemplate> templates, const StepContact& c) {
  Real size = templates[bodies[c.b].shape].curvature_radius;
  if (!c.a_is_plane) size = std::fmin(size, templates[bodies[c.a].shape].curvature_radius);
  return kPatchMatchRel * size;
}

}  // namespace

void expand_surface_contacts(std::span<const Body> bodies, std::span<const ShapeTemplate> templates,
                             std::span<const PlaneWall> planes, const PeriodicCell& cell,
                             std::span<const PairState> last, int threads, StepResults& results,
                             StepWorkspace& work) {
  std::vector<StepContact>& contacts = results.contacts;
  std::vector<std::uint32_t>& listed = work.surface_listed;
  listed.clear();
  for (std::uint32_t k = 0; k < contacts.size(); ++k)
    if (route_of(bodies, templates, contacts[k]) != ContactRoute::Convex) listed.push_back(k);
  if (listed.empty()) return;
  if (static_cast<int>(work.surface.size()) < threads) work.surface.resize(threads);
  if (work.surface_found.size() < listed.size()) work.surface_found.resize(listed.size());
  work.surface_status.resize(listed.size());
  // Jobs: a grain's contacts with one mesh wall's pieces together (margin
  // model), every other contact alone.
  std::vector<std::uint32_t>& in_jobs = work.surface_order;
  std::vector<std::array<std::uint32_t, 2>>& jobs = work.surface_jobs;
  in_jobs.resize(listed.size());
  for (std::uint32_t i = 0; i < in_jobs.size(); ++i) in_jobs[i] = i;
  // (grain, its part, wall group) of each listed contact, or (kNotMargin,
  // its position, 0).
  std::vector<std::array<std::uint32_t, 3>>& walls = work.surface_walls;
  walls.resize(listed.size());
  for (std::uint32_t i = 0; i < listed.size(); ++i) {
    const StepContact& c = contacts[listed[i]];
    const std::uint32_t g = margin_grain(bodies, templates, c);
    walls[i] = g == kNotMargin ? std::array{kNotMargin, i, 0u}
               : g == c.b      ? std::array{g, std::uint32_t{c.part_b}, bodies[c.a].group}
                               : std::array{g, std::uint32_t{c.part_a}, bodies[c.b].group};
  }
  std::stable_sort(in_jobs.begin(), in_jobs.end(), [&](std::uint32_t x, std::uint32_t y) { return walls[x] < walls[y]; });
  jobs.clear();
  for (std::uint32_t begin = 0; begin < in_jobs.size();) {
    std::uint32_t end = begin + 1;
    if (walls[in_jobs[begin]][0] != kNotMargin)
      while (end < in_jobs.size() && walls[in_jobs[end]] == walls[in_jobs[begin]]) ++end;
    jobs.push_back({begin, end});
    begin = end;
  }
  const std::int64_t n = static_cast<std::int64_t>(jobs.size());
#pragma omp parallel for num_threads(threads) schedule(dynamic, 4) if (n >= 8)
  for (std::int64_t j = 0; j < n; ++j) {
    const std::span<const std::uint32_t> members(in_jobs.data() + jobs[j][0], jobs[j][1] - jobs[j][0]);
    // Nothing may leave a parallel loop: a failure of the exact overlap (a
    // defect, never bad input) stops the run naming the pair.
    try {
      if (walls[members[0]][0] != kNotMargin) {
        find_margin_patches(bodies, templates, cell, contacts, listed, members, work.surface[thread_id()],
                            work.surface_found, work.surface_status);
      } else {
        const std::uint32_t i = members[0];
        work.surface_status[i] = find_patches(bodies, templates, planes, cell, contacts[listed[i]],
                                              work.surface[thread_id()], work.surface_found[i]);
      }
    } catch (const std::exception&) {
      for (const std::uint32_t i : members) work.surface_status[i] = GeometryStatus::Unsupported;
    }
  }

  // The list again, each listed contact replaced by its patches in slot order.
  std::vector<StepContact>& out = work.expanded;
  std::vector<PairKey>& keys = work.expanded_keys;
  out.clear(), keys.clear();
  std::vector<Vec3> anchors;
  std::vector<PatchAnchor> before;
  std::vector<std::uint32_t> slots, order;
  bool resort = false;
  std::size_t next = 0;
  for (std::uint32_t k = 0; k < contacts.size(); ++k) {
    const StepContact& c = contacts[k];
    if (next == listed.size() || listed[next] != k) {
      out.push_back(c), keys.push_back(results.keys[k]);
      continue;
    }
    const GeometryStatus status = work.surface_status[next];
    const std::vector<SurfacePatchContact>& patches = work.surface_found[next];
    ++next;
    if (status != GeometryStatus::Touching) {
      StepContact stop = c;
      stop.surface = true;
      stop.geometry.status = status;
      out.push_back(stop), keys.push_back(results.keys[k]);
      continue;
    }
    if (patches.empty()) continue;
    // Anchors in the shape frame of the body of lower id: a for two bodies
    // (bodies are in id order, a < b), the body for a plane wall.
    const Body& lo = c.a_is_plane ? bodies[c.b] : bodies[c.a];
    const Transform frame = shape_pose(templates[lo.shape], lo);
    anchors.clear();
    for (const SurfacePatchContact& p : patches) anchors.push_back(apply_inverse(frame, p.centroid));
    const PairKey key = results.keys[k];
    const bool two_compounds = !c.a_is_plane && !templates[bodies[c.a].shape].parts.empty() &&
                               !templates[bodies[c.b].shape].parts.empty();
    const PatchKeys patch_keys = patch_keys_of(key, two_compounds);
    resort |= two_compounds;
    before.clear();
    for (auto it = std::lower_bound(last.begin(), last.end(), PairKey{key.lo, key.hi, 0},
                                    [](const PairState& s, const PairKey& x) { return s.key < x; });
         it != last.end() && it->key.lo == key.lo && it->key.hi == key.hi; ++it)
      if ((it->key.parts & ~patch_keys.slot_mask) == patch_keys.prefix)
        before.push_back({it->key.parts & patch_keys.slot_mask, it->anchor});
    match_patch_slots(anchors, before, match_reach(bodies, templates, c), slots);
    if (*std::max_element(slots.begin(), slots.end()) > patch_keys.slot_mask) {  // more patches than keys: stop, naming the pair
      StepContact stop = c;
      stop.surface = true;
      stop.geometry.status = GeometryStatus::Unsupported;
      out.push_back(stop), keys.push_back(key);
      continue;
    }
    order.resize(patches.size());
    for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::uint32_t x, std::uint32_t y) { return slots[x] < slots[y]; });
    for (std::uint32_t i : order) {
      StepContact patch = c;
      patch.surface = true;
      patch.geometry = patches[i].geometry;
      patch.active = true;
      patch.anchor = anchors[i];
      out.push_back(patch);
      keys.push_back({key.lo, key.hi, patch_keys.prefix | slots[i]});
    }
  }
  if (resort) {  // two compounds' patches follow their pair's other contacts: the list sorted by key again
    std::vector<std::uint32_t> by_key(out.size());
    for (std::uint32_t i = 0; i < by_key.size(); ++i) by_key[i] = i;
    std::sort(by_key.begin(), by_key.end(), [&](std::uint32_t x, std::uint32_t y) { return keys[x] < keys[y]; });
    contacts.clear(), results.keys.clear();
    for (const std::uint32_t i : by_key) contacts.push_back(out[i]), results.keys.push_back(keys[i]);
    return;
  }
  contacts.swap(out);
  results.keys.swap(keys);
}

}  // namespace gjkdem::dem::detail
