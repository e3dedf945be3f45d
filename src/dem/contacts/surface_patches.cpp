#include "gjkdem/dem/surface_contact.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <tuple>

#include "gjkdem/contact/surface_half_space.hpp"
#include "gjkdem/tolerances.hpp"

namespace gjkdem::dem {

GeometryStatus surface_patches(const std::shared_ptr<const Surface>& shared_a, const Transform& pose_a,
                     const std::shared_ptr<const Surface>& shared_b, const Transform& pose_b,
                     SurfaceScratch& s, std::vector<SurfacePatchContact>& out) {
  out.clear();
  Transform frame;
  const SurfaceOverlap o = posed_surface_overlap(shared_a, pose_a, shared_b, pose_b, s.posed, frame);
  for (const SurfacePatch& p : o.patches) {
    const Vec3 area_a = apply_rotation(frame, p.area_a);
    ContactGeometry g;
    g.area = length(area_a);
    // A volume with no contact area: one solid wholly inside the other, or
    // through it (S_A is then zero, or rounding noise in no direction).
    switch (piece_meeting(g.area, p.volume, std::fmin(shared_a->volume, shared_b->volume))) {
      case PieceMeeting::ByArea: break;
      case PieceMeeting::WhollyInside: return GeometryStatus::Engulfed;
      case PieceMeeting::Through: return GeometryStatus::Pierced;
    }
    g.status = GeometryStatus::Touching;
    g.patch = true;
    g.normal = area_a / g.area;
    g.volume = p.volume;
    g.depth = p.volume / g.area;
    const Vec3 centroid = apply(frame, p.centroid);
    // Under every law the force is along the gradient of V: S_A on Feng's
    // line of action (as for convex overlaps, narrow_phase.cpp), level with
    // the centroid; the moment keeps the twisting couple.
    const Vec3 moment_a = apply_rotation(frame, p.area_moment_a) + cross(frame.translation, area_a);
    const Vec3 line = cross(area_a, moment_a) / dot(area_a, area_a);
    g.point = line + g.normal * dot(centroid - line, g.normal);
    g.moment = moment_a / g.area;
    out.push_back({g, centroid});
  }
  return GeometryStatus::Touching;
}

bool surfaces_meet(const std::shared_ptr<const Surface>& a, const Transform& pose_a,
                   const std::shared_ptr<const Surface>& b, const Transform& pose_b, SurfaceScratch& scratch,
                   std::vector<SurfacePatchContact>& patches) {
  return surface_patches(a, pose_a, b, pose_b, scratch, patches) != GeometryStatus::Touching ||
         !patches.empty();
}

bool placed_body_meets(const Shape& shape, const Transform& pose, const std::shared_ptr<const Surface>& surface,
                       bool surface_grain, const ShapeTemplate& other, const Transform& other_pose,
                       SurfaceScratch& scratch, std::vector<SurfacePatchContact>& patches) {
  const PartKind placed = surface_grain ? PartKind::Surface : PartKind::Convex;
  if (!other.parts.empty()) {
    for (std::uint32_t k = 0; k < other.parts.size(); ++k) {
      const TemplatePart& part = other.parts[k];
      const Transform part_pose = compose(other_pose, part.pose);
      if (pair_route(placed, part_kind(other, k)) == ContactRoute::Patches && surface && part.surface) {
        if (surfaces_meet(surface, pose, part.surface, part_pose, scratch, patches)) return true;
      } else if (intersect(shape, pose, part.given ? *part.given : part.shape, part_pose)) {
        return true;
      }
    }
    return false;
  }
  switch (pair_route(placed, part_kind(other, 0))) {
    case ContactRoute::Shell:
      if (!surface) return true;
      placed_shell_triangles(*other.shell, other_pose, aabb(shape, pose), scratch, scratch.margin_pieces);
      margin_patches(triangles_of(*surface), pose, scratch.margin_pieces, scratch, patches, scratch.margin_hosts);
      return !patches.empty();
    case ContactRoute::Patches:
      if (!surface || !other.surface) return true;
      return surfaces_meet(surface, pose, other.surface, other_pose, scratch, patches);
    case ContactRoute::Convex:
    case ContactRoute::Margin:
      break;
  }
  return true;  // the hulls are the solids, or (a surface and a mesh wall's piece) taken as meeting
}

bool plane_surface_patches(const PlaneWall& wall, const Surface& b, const Transform& pose_b, SurfaceScratch& s,
                           std::vector<SurfacePatchContact>& out) {
  out.clear();
  const SurfaceHalfSpace h = surface_half_space(b, apply_inverse(pose_b, wall.point),
                                                apply_inverse_rotation(pose_b, wall.normal), s.half_space);
  if (h.submerged) return false;
  for (const HalfSpacePiece& p : h.pieces) {
    if (!(p.cut_area > 0)) continue;
    ContactGeometry g;
    g.status = GeometryStatus::Touching;
    g.patch = true;
    g.normal = wall.normal;
    g.area = p.cut_area;
    g.volume = p.volume;
    g.depth = p.volume / p.cut_area;
    g.depth_integral = p.depth_integral;
    const Vec3 centroid = apply(pose_b, p.centroid);
    // On the wall, below the centroid of the piece (as for convex bodies
    // under the volume law): the depth integral's gradient is V through it.
    g.point = centroid + wall.normal * dot(wall.point - centroid, wall.normal);
    g.moment = cross(g.point, g.normal);
    out.push_back({g, centroid});
  }
  return true;
}

void margin_patches(const TriangleSet& grain, const Transform& pose, std::span<const MarginTriangle> triangles,
                    SurfaceScratch& s,
                    std::vector<SurfacePatchContact>& out, std::vector<std::uint32_t>& hosts) {
  out.clear(), hosts.clear();
  // In the grain's frame: the triangles' corners move instead of its vertices.
  s.margin_triangles.clear();
  for (const MarginTriangle& t : triangles)
    s.margin_triangles.push_back({{apply_inverse(pose, t.corners[0]), apply_inverse(pose, t.corners[1]),
                                   apply_inverse(pose, t.corners[2])},
                                  t.rho + grain.margin});
  surface_margin_contacts(grain, s.margin_triangles, s.margin, s.margin_contacts);
  for (const MarginContact& c : s.margin_contacts) {
    ContactGeometry g;
    g.status = GeometryStatus::Touching;
    g.normal = apply_rotation(pose, c.contact.normal);
    g.depth = c.contact.depth;
    g.point = apply(pose, c.contact.point);
    g.moment = cross(g.point, g.normal);
    out.push_back({g, g.point});
    hosts.push_back(c.triangle);
  }
}

void placed_shell_triangles(const Shell& shell, const Transform& pose, const Aabb& near, SurfaceScratch& s,
                            std::vector<MarginTriangle>& out) {
  out.clear();
  // The box in the shell's frame: the box of its corners taken back.
  constexpr Real kInf = std::numeric_limits<Real>::infinity();
  Aabb local{{kInf, kInf, kInf}, {-kInf, -kInf, -kInf}};
  for (int k = 0; k < 8; ++k) {
    const Vec3 corner{(k & 1) ? near.hi.x : near.lo.x, (k & 2) ? near.hi.y : near.lo.y, (k & 4) ? near.hi.z : near.lo.z};
    const Vec3 p = apply_inverse(pose, corner);
    local.lo = min(local.lo, p), local.hi = max(local.hi, p);
  }
  s.shell_near.clear();
  query_box_tree(shell.tree, local, s.shell_near);
  std::sort(s.shell_near.begin(), s.shell_near.end());  // in triangle order, whatever the tree's
  for (const std::uint32_t t : s.shell_near) {
    const TriangleIndices& tri = shell.triangles[t];
    out.push_back({{apply(pose, shell.vertices[tri[0]]), apply(pose, shell.vertices[tri[1]]), apply(pose, shell.vertices[tri[2]])},
                   shell.margin});
  }
}

GeometryStatus shell_patches(const ShapeTemplate& shell, const Transform& shell_pose, const ShapeTemplate& other,
                             std::uint32_t part, const PartPose& other_pose, bool shell_is_a,
                             SurfaceScratch& scratch, std::vector<SurfacePatchContact>& out) {
  const std::shared_ptr<const Surface>& surface = surface_of(other, part);
  if (!other.shell && !surface) return GeometryStatus::Unsupported;
  placed_shell_triangles(*shell.shell, shell_pose, aabb(*other_pose.shape, other_pose.pose), scratch,
                         scratch.margin_pieces);
  margin_patches(other.shell ? shell_triangles(*other.shell) : triangles_of(*surface), other_pose.pose,
                 scratch.margin_pieces, scratch, out, scratch.margin_hosts);
  if (!shell_is_a)
    for (SurfacePatchContact& p : out) p.geometry.normal = -p.geometry.normal, p.geometry.moment = -p.geometry.moment;
  return GeometryStatus::Touching;
}

bool plane_shell_patches(const PlaneWall& wall, const Shell& shell, const Transform& pose, SurfaceScratch& s,
                         std::vector<SurfacePatchContact>& out) {
  out.clear();
  const Real rho = shell.margin;
  std::vector<Real>& h = s.shell_heights;
  std::vector<Vec3>& at = s.shell_at;
  h.resize(shell.vertices.size()), at.resize(shell.vertices.size());
  bool through = true;
  for (std::size_t i = 0; i < h.size(); ++i) {
    at[i] = apply(pose, shell.vertices[i]);
    h[i] = dot(at[i] - wall.point, wall.normal);
    through = through && h[i] < -rho;
  }
  if (through) return false;
  UnionFind& patch = s.shell_corners;
  patch.reset(shell.vertices.size());
  for (const TriangleIndices& t : shell.triangles) {  // the close corners of one triangle: one patch
    std::int64_t first = -1;
    for (const std::uint32_t v : t) {
      if (!(h[v] < rho)) continue;
      if (first < 0) first = v;
      else patch.join(static_cast<std::uint32_t>(first), v);
    }
  }
  std::vector<SurfaceScratch::PlanePatch>& sums = s.shell_plane;  // by root, in corner order
  sums.clear();
  for (std::uint32_t i = 0; i < h.size(); ++i) {
    if (!(h[i] < rho)) continue;
    const std::uint32_t root = patch.find(i);
    auto it = std::find_if(sums.begin(), sums.end(), [&](const SurfaceScratch::PlanePatch& x) { return x.root == root; });
    if (it == sums.end()) sums.push_back({root, 0, 0, {}}), it = sums.end() - 1;
    const Real w = rho - h[i];
    const Vec3 point = at[i] + wall.normal * ((rho - h[i]) / 2 - rho);  // midway across the margin
    it->weight += w, it->point += w * point, it->depth = std::fmax(it->depth, w);
  }
  for (const SurfaceScratch::PlanePatch& sum : sums) {
    ContactGeometry g;
    g.status = GeometryStatus::Touching;
    g.normal = wall.normal;
    g.depth = sum.depth;
    g.point = sum.point / sum.weight;
    g.moment = cross(g.point, g.normal);
    out.push_back({g, g.point});
  }
  return true;
}

void match_patch_slots(std::span<const Vec3> anchors, std::span<const PatchAnchor> last, Real reach,
                       std::vector<std::uint32_t>& slots) {
  constexpr std::uint32_t kNone = ~0u;
  slots.assign(anchors.size(), kNone);
  struct Candidate {
    Real distance;
    std::uint32_t now, before;
  };
  std::vector<Candidate> near;
  for (std::uint32_t i = 0; i < anchors.size(); ++i)
    for (std::uint32_t j = 0; j < last.size(); ++j) {
      const Real d = length(anchors[i] - last[j].anchor);
      if (d <= reach) near.push_back({d, i, j});
    }
  std::sort(near.begin(), near.end(), [](const Candidate& x, const Candidate& y) {
    return std::tie(x.distance, x.now, x.before) < std::tie(y.distance, y.now, y.before);
  });
  std::vector<bool> taken(last.size(), false);
  // Every slot of last step stays out of reach of new patches, matched or
  // not: a vanished patch's springs are still in the store this step, and a
  // new patch must start without them.
  std::vector<std::uint32_t> used;
  for (const PatchAnchor& p : last) used.push_back(p.slot);
  for (const Candidate& c : near)
    if (slots[c.now] == kNone && !taken[c.before]) {
      slots[c.now] = last[c.before].slot;
      taken[c.before] = true;
    }
  std::sort(used.begin(), used.end());
  std::uint32_t next = 0;
  for (std::uint32_t& slot : slots) {
    if (slot != kNone) continue;
    while (std::binary_search(used.begin(), used.end(), next)) ++next;
    slot = next++;
  }
}

}  // namespace gjkdem::dem
