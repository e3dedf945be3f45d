#pragma once
// Measurements of a granular state in a region (a box, a cylinder, a ball): the solid fraction (the
// grains clipped by the region), the mean coordination number, the
// Love-Weber stress and the normal contact forces. They read the world's
// bodies and a list of touching contacts, so that they apply to a live world
// (touching_contacts) and to a frame read back from a run folder alike
// (`gjkdem analyze`, io/analysis.hpp). Conventions: docs/measurements.md.
#include <cstdint>
#include <optional>
#include <unordered_map>
#include <span>
#include <utility>
#include <vector>

#include "gjkdem/contact/overlap.hpp"
#include "gjkdem/contact/surface_overlap.hpp"
#include "gjkdem/dem/round_region.hpp"
#include "gjkdem/dem/world.hpp"

namespace gjkdem::dem {

/// An axis-aligned box of the world (m), or a cylinder or ball (`round`;
/// lo and hi are then ignored).
struct MeasureRegion {
  Vec3 lo, hi;
  std::optional<RoundRegion> round{};
  Real volume() const noexcept {
    return round ? round_volume(*round) : (hi.x - lo.x) * (hi.y - lo.y) * (hi.z - lo.z);
  }
  friend bool operator==(const MeasureRegion&, const MeasureRegion&) = default;
};

/// A touching contact: the force acts on `second`, its opposite on `first`.
struct MeasuredContact {
  std::uint32_t first = 0;      ///< body index, or plane wall index when first_is_plane
  bool first_is_plane = false;
  std::uint32_t second = 0;     ///< body index
  Vec3 point, normal, force;    ///< world (m), unit first -> second, N
};

struct Measures {
  Real region_volume = 0;     ///< m^3
  Real solid_volume = 0;      ///< of the grains inside the region, their periodic images included (m^3)
  Real solid_fraction = 0;    ///< solid_volume / region_volume
  std::size_t grains = 0;     ///< moving bodies whose centre of mass is in the region
  Real coordination = 0;      ///< touching contacts per such grain, walls' included (0 without grains)
  std::size_t contacts = 0;   ///< contacts of at least one such grain
  Real mean_normal_force = 0; ///< mean |F . n| over those contacts (N)
  /// Love-Weber stress of the grains in the region, compression positive
  /// (Pa): -1/V sum over grains p, contacts c of p: (x_c - x_p) (x) f_c, the
  /// symmetric part.
  Mat3 stress{{Vec3{}, Vec3{}, Vec3{}}};
  Real pressure = 0;          ///< trace(stress) / 3 (Pa)
  std::vector<Real> normal_forces;  ///< |F . n| of those contacts (N), in contact order
};

/// Clipping buffers, and how each template's parts are clipped, kept between calls.
struct MeasureWorkspace {
  struct ClippedShape {
    bool tessellated = false;  ///< curved: its tessellation is clipped
    Shape tessellation;
    Real volume = 0;           ///< of the solid clipped (the shape or its tessellation)
  };
  OverlapWorkspace overlap;
  std::unordered_map<std::uint64_t, ClippedShape> clipped;  ///< key: template << 32 | part
  /// The region as a solid at its pose (a box, or a round region's
  /// tessellation of kMeasureTessellation directions), made for
  /// `region_for`; as a closed surface in its own frame, made once a surface
  /// grain is met (it clips them exactly); that surface placed in a grain's
  /// frame.
  std::optional<MeasureRegion> region_for;
  Shape region_solid;
  Transform region_pose;
  std::optional<Surface> region_surface;
  Surface placed;
  SurfaceOverlapWorkspace surface_overlap;
  /// The region's planes near a shell and a triangle being clipped by them.
  std::vector<OverlapWorkspace::Plane> planes;
  std::vector<Vec3> polygon, clipped_polygon;
};

/// Directions of the tessellation of curved grains clipped by the region.
inline constexpr int kMeasureTessellation = 2048;

/// The touching contacts of the world's last force evaluation.
std::vector<MeasuredContact> touching_contacts(const World& world);

/// The box around the moving bodies (each its reach around its centre);
/// none when there are none.
std::optional<MeasureRegion> moving_bodies_box(const World& world);

/// Volume (m^3) of the part of a body inside the region: its shape (or each
/// part) clipped by the region, exact for polytope-like shapes in a box; a
/// curved one is clipped as its tessellation (kMeasureTessellation
/// directions), and so is a round region's curved side. The
/// clipped volume is scaled by the body's volume over the clipped solid's, so
/// that a body wholly inside counts whole (the volume law's contact shapes
/// are inscribed tessellations of the bodies' shapes). A surface grain (or a
/// compound's surface part) is clipped as its own surface, convex or not
/// (surface_overlap), exactly; a thin shell as its plates: the area of its
/// triangles inside times its thickness.
Real volume_inside(const World& world, const Body& body, const MeasureRegion& region, MeasureWorkspace& work);

/// Throws std::invalid_argument for a region that is empty or not finite.
Measures measure(const World& world, std::span<const MeasuredContact> contacts, const MeasureRegion& region,
                 MeasureWorkspace& work);

}  // namespace gjkdem::dem
