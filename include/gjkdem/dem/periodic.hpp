#pragma once
// Periodic boundaries: on each periodic axis the world repeats with period
// hi - lo. A moving body that leaves the cell [lo, hi) on one side enters it
// on the other (its box anchor moves with it, so its box stays valid), and
// bodies touch across the boundary: the broad phase sweeps, besides every
// box, its images shifted by one period where they reach within the widest
// box of a face, and each candidate pair carries the image of its second
// body (StepContact::shift). A pair touches through at most one image: the
// builder refuses cells shorter than four of the largest body's reach
// (skin included) on a periodic axis. Pair keys stay the bodies' ids, so a
// contact keeps its springs while a body crosses.
//
// The cell may deform (CellControl): its edge vectors are a = (Lx, 0, 0),
// b = (xy, Ly, 0), c = (xz, yz, Lz) (an upper-triangular cell, as LAMMPS's
// triclinic boxes: the tilts xy, xz, yz shear it), and they change with an
// upper-triangular velocity gradient L (dH/dt = L H): per component a given
// strain rate, or a servo driving the contacts' stress to a target. The
// world's velocity field then holds an affine part L (x - centre): a change
// of L changes the bodies' velocities by its difference (their motion
// relative to the field stays), the image of a body one lattice vector s
// away moves with the body's velocity plus L s, and a body wrapping across
// a face takes that difference with it. A shear rate alone (L_xz) is the
// Lees-Edwards boundary: a simple shear without walls. A tilt beyond half
// the edge it leans along is taken back by one edge (the same lattice). The
// live cell is state (World::cell); the settings keep the cell the scene
// gave.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "gjkdem/math/vec3.hpp"
#include "gjkdem/shape/aabb.hpp"

namespace gjkdem::dem {

struct World;
struct Body;
struct Makeup;
struct BoxCache;
struct DomainRole;
struct StepWorkspace;

struct PeriodicCell {
  bool axes[3] = {false, false, false};  ///< periodic on x, y, z
  Vec3 lo, hi;     ///< the cell's corner and lo + (Lx, Ly, Lz), on the periodic axes (m)
  Vec3 tilt;       ///< xy, xz, yz (m): b = (xy, Ly, 0), c = (xz, yz, Lz); zero unless sheared
  bool active() const noexcept { return axes[0] || axes[1] || axes[2]; }
};

/// Components of a velocity gradient or a stress on the cell's axes, in
/// this order: xx, yy, zz, xy, xz, yz. Gradients are upper triangular
/// (L_xy: the x velocity's change along y); stresses symmetric.
using CellTensor = std::array<Real, 6>;
inline constexpr int kXY = 3, kXZ = 4, kYZ = 5;
inline constexpr const char* kCellComponents[6] = {"x", "y", "z", "xy", "xz", "yz"};

/// The periodic cell's state in a world (World::cell): the cell now (the
/// settings' cell, deformed by its control), its velocity gradient in the
/// last step (1/s) and the contacts' stress at the last force evaluation
/// (Pa, compression positive: the symmetric part of sum f x branch over the
/// contacts, divided by the cell's volume). A checkpoint holds all three.
struct CellState {
  PeriodicCell now;
  CellTensor rate{};
  CellTensor stress{};
};

/// How each component of the velocity gradient is set: held at zero, at a
/// strain rate, or by a servo driving that component of the stress to a
/// target.
enum class CellMode : std::uint8_t { Fixed, StrainRate, Stress };

struct CellControl {
  std::array<CellMode, 6> mode{};  ///< per component (CellTensor order)
  /// Per component: the rate (1/s; positive stretches, L_xz > 0 moves the
  /// top (z) faster along x) or the target stress (Pa, compression
  /// positive), by mode.
  CellTensor value{};
  /// The servo's largest rate (1/s): a component whose stress is off its
  /// target by the largest target's size or more deforms at it, nearer in
  /// proportion (so at rest the stress is the target).
  Real max_strain_rate = 0;
  bool deforms() const noexcept {
    for (const CellMode m : mode)
      if (m != CellMode::Fixed) return true;
    return false;
  }
  bool servo() const noexcept {
    for (const CellMode m : mode)
      if (m == CellMode::Stress) return true;
    return false;
  }
};

/// The cell's edge vectors a, b, c (periodic axes only; tilts as given).
inline Vec3 cell_edge(const PeriodicCell& cell, int axis) noexcept {
  const Vec3 length = cell.hi - cell.lo;
  if (axis == 0) return {length.x, 0, 0};
  if (axis == 1) return {cell.tilt.x, length.y, 0};
  return {cell.tilt.y, cell.tilt.z, length.z};
}
inline Vec3 cell_centre(const PeriodicCell& cell) noexcept {
  return cell.lo + (cell_edge(cell, 0) + cell_edge(cell, 1) + cell_edge(cell, 2)) * 0.5;
}
/// The cell's volume: the product of its periodic lengths (m^3 when all
/// three axes are periodic; tilts do not change it).
inline Real cell_volume(const PeriodicCell& cell) noexcept {
  Real v = 1;
  for (int a = 0; a < 3; ++a)
    if (cell.axes[a]) v *= cell.hi[a] - cell.lo[a];
  return v;
}
/// L v for an upper-triangular gradient L: how fast a point v from another
/// moves away from it in the affine field (an image: v its shift).
inline Vec3 affine_velocity(const CellTensor& l, const Vec3& v) noexcept {
  return {l[0] * v.x + l[kXY] * v.y + l[kXZ] * v.z, l[1] * v.y + l[kYZ] * v.z, l[2] * v.z};
}
/// The lattice vector n_a a + n_b b + n_c c.
inline Vec3 lattice_vector(const PeriodicCell& cell, int na, int nb, int nc) noexcept {
  return cell_edge(cell, 0) * static_cast<Real>(na) + cell_edge(cell, 1) * static_cast<Real>(nb) +
         cell_edge(cell, 2) * static_cast<Real>(nc);
}
/// d moved by the lattice vector that brings it nearest to zero on the
/// periodic axes (for the short vectors between touching bodies).
Vec3 nearest_image(const PeriodicCell& cell, Vec3 d) noexcept;

/// An image: one period back, none or forward on each axis, as a code
/// 0..26 (13: no shift).
inline constexpr std::uint8_t kNoImage = 13;
inline std::uint8_t image_code(const int shift[3]) noexcept {
  return static_cast<std::uint8_t>((shift[0] + 1) + 3 * (shift[1] + 1) + 9 * (shift[2] + 1));
}
inline Vec3 image_shift(const PeriodicCell& cell, std::uint8_t code) noexcept {
  return lattice_vector(cell, code % 3 - 1, code / 3 % 3 - 1, code / 9 - 1);
}

/// The shifts of the images a body may touch through: no shift first, then
/// one period either way on each periodic axis (only no shift without a cell).
std::vector<Vec3> image_shifts(const PeriodicCell& cell);

/// Adds a contact's share to the symmetric sum of f x branch (the cell's
/// stress times its volume): force on b, branch from a's centre (or the
/// wall's contact point) to b's centre or image.
inline void add_virial(CellTensor& sum, const Vec3& force, const Vec3& branch) noexcept {
  sum[0] += force.x * branch.x, sum[1] += force.y * branch.y, sum[2] += force.z * branch.z;
  sum[kXY] += 0.5 * (force.x * branch.y + force.y * branch.x);
  sum[kXZ] += 0.5 * (force.x * branch.z + force.z * branch.x);
  sum[kYZ] += 0.5 * (force.y * branch.z + force.z * branch.y);
}

/// The moving bodies a periodic cell moves, and where the kinetic energy
/// its field gives them goes (the cell's work on them): a whole world
/// (`domain` null) adds it to `wall_work` in body order; a domain moves
/// only the bodies it owns (their owners move the others) and lists it per
/// body (DomainRole::field_work, wrap_work) for rank 0 to sum in id order.
struct CellBodies {
  std::span<Body> bodies;
  const Makeup* makeup = nullptr;
  DomainRole* domain = nullptr;
  Real* wall_work = nullptr;
};

/// Puts the moving bodies back into the cell, moving their box anchors and
/// boxes with them (and their velocities by the affine velocity `rate` of
/// the move in a deforming cell). Returns how many crossed.
std::size_t wrap_bodies(const PeriodicCell& cell, const CellTensor& rate, BoxCache& boxes, const CellBodies& moved);

/// A deforming cell, before the drift of a step: sets the velocity
/// gradient `rate` (the servo's from `stress`, the contacts' stress at the
/// last force evaluation) and changes the moving bodies' velocities by the
/// change of the affine field about the cell's centre.
void control_cell(const CellControl& control, const CellTensor& stress, const PeriodicCell& cell, CellTensor& rate,
                  const CellBodies& moved);

/// Moves the cell's edges by the velocity gradient over dt (with the
/// drift), taking back a tilt beyond half its edge. Returns true when the
/// lattice was taken back (images change: candidates must be found again).
bool deform_cell(PeriodicCell& cell, const CellTensor& rate, Real dt);

/// How far any image may have moved since the last candidate search (m):
/// the broad phase counts it as motion.
Real cell_drift(const PeriodicCell& now, const PeriodicCell& searched) noexcept;

/// The cell's width across axis a: the distance between its two faces
/// crossing that axis (the length on the axis for an unsheared cell).
Real cell_width(const PeriodicCell& cell, int axis) noexcept;

/// The candidate pairs of a periodic world with their images, the boxes
/// searched in `cell` (the search cell: World::search): fills
/// work.candidates and work.candidate_images from the moving and static sets
/// that find_candidates prepared.
void find_periodic_candidates(std::span<const Body> bodies, std::span<const Aabb> boxes, const PeriodicCell& cell,
                              int threads, StepWorkspace& work);

}  // namespace gjkdem::dem
