#include "size_mix.hpp"

#include "gjkdem/io/scene.hpp"
#include "gjkdem/shape/mass_properties.hpp"
#include "gjkdem/shape/shape_factories.hpp"
#include "gjkdem/shape/surface.hpp"

namespace gjkdem::io::detail {
namespace {

// A surface scaled by k, checked again: scaling rounds every vertex.
std::shared_ptr<const Surface> scaled_surface(const std::shared_ptr<const Surface>& surface, Real k,
                                              const std::string& where) {
  if (k == 1) return surface;
  std::vector<Vec3> vertices = surface->vertices;
  for (Vec3& vertex : vertices) vertex *= k;
  try {
    return std::make_shared<const Surface>(make_surface(std::move(vertices), surface->triangles));
  } catch (const SurfaceError& e) {
    throw SceneError(where + ": the surface scaled by " + std::to_string(k) + " is no longer one: " + e.what());
  }
}

// The volume of a shape as a scene gives it (a compound's: its parts' sum).
Real volume_of(const dem::BodyShape& shape) {
  if (shape.surface) return shape.surface->volume;
  if (!dem::is_compound(shape)) return mass_properties(shape.shape).volume;
  Real volume = shape.parts.empty() ? 0 : mass_properties(shape.parts).volume;
  for (const dem::PlacedSurface& p : shape.surface_parts) volume += p.surface->volume;
  return volume;
}

}  // namespace

SampledMix sample_mix(std::span<const MixPart> parts, std::span<const SizeClass> given, std::int64_t per_group,
                      bool by_mass, std::mt19937_64& rng) {
  const bool sized = !given.empty();
  const std::vector<SizeClass> classes = sized ? std::vector<SizeClass>(given.begin(), given.end())
                                               : std::vector<SizeClass>{{0, 0, 1}};
  Real part_total = 0;
  for (const MixPart& p : parts) part_total += p.fraction;
  SampledMix mix;
  for (const MixPart& part : parts) {
    const std::optional<PolyhedronSpec>& poly = part.polyhedron;
    // Number weight of each variant: the part's fraction spread over its
    // size classes by their mass fractions (mass per body from its volume).
    std::vector<std::vector<Real>> volumes(classes.size());
    for (std::size_t c = 0; c < classes.size(); ++c) {
      std::uniform_real_distribution<double> draw(sized ? classes[c].lo : poly ? poly->size_lo : 0,
                                                  sized ? classes[c].hi : poly ? poly->size_hi : 0);
      for (std::int64_t v = 0; v < per_group; ++v) {
        dem::BodyShape shape;
        if (poly) {
          shape.shape = random_polyhedron(static_cast<int>(poly->vertices), draw(rng), rng);
        } else {
          const Real k = sized ? draw(rng) / part.base_size : 1;
          shape = part.base;
          shape.shape = scaled(part.base.shape, k);
          shape.pose.translation *= k;
          for (PlacedShape& p : shape.parts) p.shape = scaled(p.shape, k), p.pose.translation *= k;
          if (shape.surface) shape.surface = scaled_surface(shape.surface, k, part.where);
          for (dem::PlacedSurface& p : shape.surface_parts)
            p.surface = scaled_surface(p.surface, k, part.where), p.pose.translation *= k;
        }
        volumes[c].push_back(volume_of(shape));
        mix.variants.push_back(std::move(shape));
      }
    }
    std::vector<Real> class_weight(classes.size());  // bodies per unit of the part's fraction
    Real per_body_total = 0;
    for (std::size_t c = 0; c < classes.size(); ++c) {
      Real mean = 0;
      for (const Real v : volumes[c]) mean += v / static_cast<Real>(volumes[c].size());
      if (!(mean > 0)) throw SceneError(part.where + ": a shape without volume cannot take a mass fraction");
      class_weight[c] = classes[c].mass_fraction / mean;  // number in class c per unit mass of the part
      per_body_total += class_weight[c];
    }
    for (std::size_t c = 0; c < classes.size(); ++c) {
      // fractions by mass: the part's mass fraction; by number: its number fraction.
      const Real w = by_mass ? part.fraction / part_total * class_weight[c]
                             : part.fraction / part_total * class_weight[c] / per_body_total;
      for (std::int64_t v = 0; v < per_group; ++v) mix.weights.push_back(w / static_cast<Real>(per_group));
    }
  }
  return mix;
}

}  // namespace gjkdem::io::detail
