#pragma once
// The seed text's triangle-pair query GJK(A, B, C, D, E, F, rho, tol): are the
// triangles ABC and DEF closer than the margin rho? Answered in closed form,
// not by iteration: the distance between two triangles is zero when an edge of
// one crosses the other, else the least of the 9 edge-edge distances and the 6
// distances of a corner to the other's face (where it projects inside). That
// makes the answer exact up to round-off (no tolerance: the seed's `tol` has
// nothing left to bound) and lets one kernel run many pairs at once.
//
// The batched kernel takes pairs in blocks of kTriangleLanes (structure of
// arrays inside a block) and runs them with AVX-512 or AVX2 where the
// processor has it, else with SSE2 (every x86-64); all give the same bits,
// lane for lane, as the one-pair triangle_contact.
#include <cstddef>
#include <vector>

#include "gjkdem/collide/status.hpp"
#include "gjkdem/math/vec3.hpp"

namespace gjkdem {

struct TriangleContact {
  bool contact = false;  ///< distance <= rho (touching or overlapping counts)
  Real distance = 0;     ///< >= 0; 0 when the triangles touch or intersect
  Vec3 witness_a;        ///< closest point on ABC; where they intersect, a point of both
  Vec3 witness_b;        ///< closest point on DEF (= witness_a when they intersect)
  Vec3 normal;           ///< unit, ABC -> DEF; zero when they touch or intersect
  GjkStatus status = GjkStatus::Separated;  ///< Separated or Intersecting (distance 0)
  int iterations = 0;  ///< always 0: the closed form does not iterate (kept from the GJK version)
};

/// `rho` >= 0 is the contact margin (same unit as the points).
TriangleContact triangle_contact(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, const Vec3& e,
                                 const Vec3& f, Real rho) noexcept;

/// Pairs per block of the batched kernel.
inline constexpr int kTriangleLanes = 8;

/// kTriangleLanes triangle pairs, coordinates by corner, axis, then pair.
struct TrianglePairBlock {
  Real a[3][3][kTriangleLanes];  ///< a[corner][axis][lane]: the first triangles (ABC)
  Real b[3][3][kTriangleLanes];  ///< the second triangles (DEF)
};

/// The kernel's answers for one block: distance and closest points per pair.
struct TriangleDistanceBlock {
  Real distance[kTriangleLanes];      ///< 0 where the pair touches or intersects
  Real witness_a[3][kTriangleLanes];  ///< [axis][lane]: on the first triangle
  Real witness_b[3][kTriangleLanes];  ///< on the second (= witness_a at distance 0)
};

/// A list of triangle pairs laid out for the kernel. Lanes past `size` in the
/// last block repeat its first pair, so every lane holds a valid pair.
struct TrianglePairs {
  std::vector<TrianglePairBlock> blocks;
  std::size_t size = 0;

  void clear() noexcept { blocks.clear(); size = 0; }
  void push_back(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, const Vec3& e, const Vec3& f);
};

/// The instruction sets the kernel can run on; Best is the widest this
/// processor has (AVX-512F, else AVX2, else SSE2).
enum class TriangleSimd { Best, Sse2, Avx2, Avx512 };

/// True when this processor runs `simd` (Best and Sse2 always).
bool triangle_simd_available(TriangleSimd simd) noexcept;

/// What Best runs on this processor (never Best).
TriangleSimd triangle_simd_best() noexcept;

/// "sse2", "avx2", "avx512" or "best".
const char* triangle_simd_name(TriangleSimd simd) noexcept;

/// Distances and closest points of `count` blocks of pairs. Every coordinate
/// must be finite. `simd` other than Best is for tests and benchmarks; it must
/// be available.
void triangle_distances(const TrianglePairBlock* pairs, TriangleDistanceBlock* out, std::size_t count,
                        TriangleSimd simd = TriangleSimd::Best) noexcept;

/// All pairs of `pairs`; `out` is resized to its blocks.
void triangle_distances(const TrianglePairs& pairs, std::vector<TriangleDistanceBlock>& out,
                        TriangleSimd simd = TriangleSimd::Best);

}  // namespace gjkdem
