#include "gjkdem/dem/split_body.hpp"

#include <stdexcept>

#include "gjkdem/dem/rigid_rotation.hpp"
#include "gjkdem/shape/shape_factories.hpp"
#include "gjkdem/shape/split.hpp"

namespace gjkdem::dem {
namespace {

// The template's solid as a polytope, or none.
std::optional<Polytope> solid_polytope_of(const ShapeTemplate& t) {
  if (!can_split(t)) return std::nullopt;
  if (const Polytope* p = std::get_if<Polytope>(&t.shape.core)) return *p;
  if (const Box* box = std::get_if<Box>(&t.shape.core)) return box_polytope(*box);
  return std::nullopt;
}

// A fragment's angular momentum R diag(moments) R^T w, R its principal frame.
Vec3 principal_times(const Quat& r, const Vec3& moments, const Vec3& w) {
  const Vec3 local = rotate(conjugate(r), w);
  return rotate(r, Vec3{moments.x * local.x, moments.y * local.y, moments.z * local.z});
}

}  // namespace

bool can_split(const ShapeTemplate& t) noexcept {
  return t.parts.empty() && !t.surface_grain && !t.given && t.shape.margin == 0 &&
         (std::holds_alternative<Polytope>(t.shape.core) || std::holds_alternative<Box>(t.shape.core));
}

std::vector<Fragment> split_body(const ShapeTemplate& t, const Body& b, Real density, const Vec3& point,
                                 const Vec3& normal) {
  if (b.fixed) throw std::invalid_argument("split_body: fixed bodies do not split");
  if (!is_finite(point)) throw std::invalid_argument("split_body: the plane's point must be finite");
  const std::optional<Polytope> solid = solid_polytope_of(t);
  if (!solid)
    throw std::invalid_argument("split_body: only solid polyhedra and boxes split (curved shapes, compounds and "
                                "surface grains do not yet)");
  const Transform pose = shape_pose(t, b);
  const Vec3 local_normal = apply_inverse_rotation(pose, normal);
  const PolytopeSplit pieces = split_polytope(*solid, local_normal, dot(local_normal, apply_inverse(pose, point)));
  if (!pieces.below || !pieces.above) return {};

  const Vec3 spin = angular_velocity(b.orientation, b.angular_momentum, t.principal.moments * density);
  const Quat shape_q = shape_orientation(t, b);
  std::vector<Fragment> out;
  for (const Polytope& piece : {*pieces.below, *pieces.above}) {
    // The piece about its own centroid: its shape frame is the grain's moved
    // there (same axes), so that its reach, and its box, fit it.
    const Vec3 centre = piece.data->centroid;
    std::vector<Vec3> moved(piece.data->vertices.begin(), piece.data->vertices.end());
    for (Vec3& v : moved) v -= centre;
    Fragment f;
    f.shape = Shape{make_polytope(moved)};
    f.unit_mass = mass_properties(f.shape);
    f.principal = principal_axes(f.unit_mass.inertia);
    f.position = apply(pose, centre + f.unit_mass.centroid);
    f.orientation = normalized(shape_q * f.principal.rotation);
    f.velocity = b.velocity + cross(spin, f.position - b.position);
    f.angular_momentum = principal_times(f.orientation, f.principal.moments * density, spin);
    out.push_back(std::move(f));
  }
  return out;
}

}  // namespace gjkdem::dem
