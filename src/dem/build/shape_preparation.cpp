// Every template made ready for the contact model (world_builder.hpp): under
// the volume law, curved shapes as inscribed polytopes and big hulls' kept
// surfaces; in a world with surface grains, every other shape's boundary.
#include "gjkdem/dem/world_builder.hpp"

#include <algorithm>
#include <cmath>

#include "build/builder_detail.hpp"
#include "gjkdem/collide/query.hpp"
#include "gjkdem/dem/surface_contact.hpp"
#include "gjkdem/shape/polytope.hpp"
#include "gjkdem/shape/tessellate.hpp"

namespace gjkdem::dem {

namespace detail {

// A solid polytope or box without margin: what the volume law clips.
bool solid_polytope(const Shape& s) {
  if (s.margin != 0) return false;
  if (const auto* b = std::get_if<Box>(&s.core))
    return b->half_extents.x > 0 && b->half_extents.y > 0 && b->half_extents.z > 0;
  if (const auto* p = std::get_if<Polytope>(&s.core)) return !p->data->triangles.empty();
  return false;
}

// Flat cores without a margin: a point, a segment, a triangle, a flat
// polytope or box. Curved cores and anything with a margin have volume.
bool without_volume(const Shape& s) {
  return s.margin == 0 && !solid_polytope(s) &&
         (std::holds_alternative<Point>(s.core) || std::holds_alternative<Segment>(s.core) ||
          std::holds_alternative<Triangle>(s.core) || std::holds_alternative<Polytope>(s.core) ||
          std::holds_alternative<Box>(s.core));
}

// The closed surface surface grains meet a convex shape of volume by: a
// solid polytope's hull triangles (a big hull's own, kept with it:
// hull_surface), a curved shape's inscribed tessellation (throws
// SurfaceError for a flat one).
std::shared_ptr<const Surface> boundary_surface(const Shape& s, int tessellation) {
  if (std::holds_alternative<Box>(s.core) && s.margin == 0)
    return std::make_shared<const Surface>(box_surface(std::get<Box>(s.core)));
  if (solid_polytope(s)) {
    const Polytope& hull = std::get<Polytope>(s.core);
    if (std::shared_ptr<const Surface> kept = hull_surface(hull)) return kept;
    return std::make_shared<const Surface>(polytope_surface(hull));
  }
  return std::make_shared<const Surface>(polytope_surface(tessellate(s, tessellation).polytope));
}

}  // namespace detail

using detail::boundary_surface;
using detail::solid_polytope;
using detail::without_volume;

// Every shape gets what the contact model needs, moving or fixed: the volume
// law clips solid polytopes, so every other shape becomes the inscribed
// polytope of a tessellation (its mass properties stay those of the shape);
// shapes without volume cannot take part. The penetration laws take every shape.
void WorldBuilder::prepare_shapes() {
  if (settings_.model != ContactModel::Volume) return;
  std::vector<std::size_t> user(world_.templates.size(), 0);  // a body of each template, for messages
  for (std::size_t i = world_.bodies.size(); i-- > 0;) user[world_.bodies[i].shape] = i;
  for (std::size_t t = prepared_templates_; t < world_.templates.size(); ++t) {
    const std::string& who = labels_.empty() ? std::string("a body") : labels_[user[t]];
    if (world_.templates[t].surface_grain) continue;  // its hull only bounds it
    if (world_.templates[t].parts.empty()) {
      prepare_for_volume_law(world_.templates[t].shape, world_.templates[t].given, who, user[t]);
      make_hull_surface(world_.templates[t].shape);
    } else {  // the hull stays: it only bounds the parts
      for (TemplatePart& part : world_.templates[t].parts)
        if (!part.surface_grain) prepare_for_volume_law(part.shape, part.given, who, user[t]), make_hull_surface(part.shape);
    }
  }
}

// In a world with surface grains every other template, and every part of a
// compound, gets the closed surface their contacts take: a solid
// polytope's hull triangles, a curved shape's inscribed tessellation.
// Shapes without volume get none (their contacts with surface grains stop
// the run as unsupported pairs), nor do a mesh wall's triangles under the
// penetration laws (the margin model meets the grains' triangles).
void WorldBuilder::prepare_surfaces() {
  std::vector<ShapeTemplate>& templates = world_.templates;
  if (std::none_of(templates.begin(), templates.end(), [](const ShapeTemplate& t) { return holds_surface(t); })) return;
  constexpr std::size_t kNoBody = ~std::size_t{0};  // an inflow's template
  std::vector<std::size_t> user(templates.size(), kNoBody);
  for (std::size_t i = world_.bodies.size(); i-- > 0;) user[world_.bodies[i].shape] = i;
  for (std::size_t k = 0; k < templates.size(); ++k) {
    ShapeTemplate& t = templates[k];
    if (t.surface || t.shell) continue;  // a shell meets surfaces by its own triangles
    const std::string who = user[k] == kNoBody ? "an inflow's shape"
                            : labels_.empty()   ? std::string("a body")
                                                : labels_[user[k]];
    const std::vector<std::uint32_t> at =
        user[k] == kNoBody ? std::vector<std::uint32_t>{} : std::vector<std::uint32_t>{static_cast<std::uint32_t>(user[k])};
    const auto boundary = [&](const Shape& s) {
      try {
        return boundary_surface(s, settings_.tessellation);
      } catch (const SurfaceError& e) {
        throw BuildError(who + ": its boundary cannot meet surface grains: " + e.what(), at);
      }
    };
    if (!t.parts.empty()) {
      for (TemplatePart& part : t.parts)
        if (!part.surface && !without_volume(part.shape)) part.surface = boundary(part.shape);
    } else if (!without_volume(t.shape) && !margin_piece(t)) {  // a mesh wall's piece meets them by its margin
      t.surface = boundary(t.shape);
    }
  }
}

// Under the volume law: a solid polytope as it is, a curved shape as its
// inscribed polytope; a shape without volume is refused.
void WorldBuilder::prepare_for_volume_law(Shape& s, std::optional<Shape>& given, const std::string& who,
                                          std::size_t user) const {
  if (solid_polytope(s)) return;
  if (without_volume(s))
    throw BuildError(who + ": a shape without volume cannot take part in the volume law (give it a margin or "
                           "thickness, or use model \"hertz\" or \"linear\")",
                     {static_cast<std::uint32_t>(user)});
  Tessellation tess = tessellate(s, settings_.tessellation);
  if (!solid_polytope(Shape{tess.polytope}))
    throw BuildError(who + ": the tessellation of this shape for the volume law is flat");
  given = s;
  s = Shape{tess.polytope};
}

}  // namespace gjkdem::dem
