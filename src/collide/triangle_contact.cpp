// The seed's triangle-pair query in closed form, one pair or many: the kernel
// (triangle_kernel.inl) compiled for SSE2, AVX2 and AVX-512, and the dispatch
// between them.
#include "gjkdem/collide/triangle_contact.hpp"

#include <cmath>
#if defined(__x86_64__)
#include <immintrin.h>
#endif
#include <cstring>
#include <limits>
#include <type_traits>

namespace gjkdem {
namespace {

#define GJKDEM_LANE_INLINE [[gnu::always_inline]] inline

// 32- and 64-byte vectors live only inside the AVX2 and AVX-512 functions (all
// inlined); GCC warns about their ABI late, after any pop, so the warning is
// off for the file.
#pragma GCC diagnostic ignored "-Wpsabi"

using V2 = double __attribute__((vector_size(16)));
using V4 = double __attribute__((vector_size(32)));
using V8 = double __attribute__((vector_size(64)));

// The paths round alike only without fused multiply-adds: CMake compiles this
// file with -ffp-contract=off (which matters where the flags allow FMA, such
// as -march=native; a pragma optimize would cost a third of the speed).
#define GJKDEM_TRIANGLE_KERNEL_WIDTH 2
namespace sse2 {
#include "triangle_kernel.inl"
}  // namespace sse2
#undef GJKDEM_TRIANGLE_KERNEL_WIDTH

void run_blocks_sse2(const TrianglePairBlock* in, TriangleDistanceBlock* out, std::size_t count) {
  sse2::run_blocks<V2>(in, out, count);
}
void run_one_pair(const TrianglePairBlock& in, TriangleDistanceBlock& out) { sse2::run_lanes<double>(in, out, 0); }

#if defined(__x86_64__) && defined(__GNUC__)
#define GJKDEM_HAVE_WIDE_PATHS 1
#pragma GCC push_options
#pragma GCC target("avx2")
#define GJKDEM_TRIANGLE_KERNEL_WIDTH 4
namespace avx2 {
#include "triangle_kernel.inl"
}  // namespace avx2
#undef GJKDEM_TRIANGLE_KERNEL_WIDTH
void run_blocks_avx2(const TrianglePairBlock* in, TriangleDistanceBlock* out, std::size_t count) {
  avx2::run_blocks<V4>(in, out, count);
}
#pragma GCC pop_options

// AVX-512: a whole block in one 8-lane pass, its 32 registers spilling less
// and its masks selecting in one instruction (1.7x AVX2 here).
#pragma GCC push_options
#pragma GCC target("avx512f")
#define GJKDEM_TRIANGLE_KERNEL_WIDTH 8
namespace avx512 {
#include "triangle_kernel.inl"
}  // namespace avx512
#undef GJKDEM_TRIANGLE_KERNEL_WIDTH
void run_blocks_avx512(const TrianglePairBlock* in, TriangleDistanceBlock* out, std::size_t count) {
  avx512::run_blocks<V8>(in, out, count);
}
#pragma GCC pop_options
#endif

}  // namespace

void TrianglePairs::push_back(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, const Vec3& e,
                              const Vec3& f) {
  const int lane = static_cast<int>(size % kTriangleLanes);
  const Vec3 corners[2][3] = {{a, b, c}, {d, e, f}};
  const auto put = [&](TrianglePairBlock& block, int l) {
    for (int corner = 0; corner < 3; ++corner)
      for (int axis = 0; axis < 3; ++axis) {
        block.a[corner][axis][l] = corners[0][corner][axis];
        block.b[corner][axis][l] = corners[1][corner][axis];
      }
  };
  if (lane == 0) {
    blocks.emplace_back();
    for (int l = 0; l < kTriangleLanes; ++l) put(blocks.back(), l);  // the padding lanes too
  } else {
    put(blocks.back(), lane);
  }
  ++size;
}

bool triangle_simd_available(TriangleSimd simd) noexcept {
#ifdef GJKDEM_HAVE_WIDE_PATHS
  if (simd == TriangleSimd::Avx2) return __builtin_cpu_supports("avx2");
  if (simd == TriangleSimd::Avx512) return __builtin_cpu_supports("avx512f");
  return true;
#else
  return simd == TriangleSimd::Best || simd == TriangleSimd::Sse2;
#endif
}

TriangleSimd triangle_simd_best() noexcept {
  static const TriangleSimd best = triangle_simd_available(TriangleSimd::Avx512) ? TriangleSimd::Avx512
                                   : triangle_simd_available(TriangleSimd::Avx2) ? TriangleSimd::Avx2
                                                                                 : TriangleSimd::Sse2;
  return best;
}

const char* triangle_simd_name(TriangleSimd simd) noexcept {
  switch (simd) {
    case TriangleSimd::Sse2: return "sse2";
    case TriangleSimd::Avx2: return "avx2";
    case TriangleSimd::Avx512: return "avx512";
    case TriangleSimd::Best: break;
  }
  return "best";
}

void triangle_distances(const TrianglePairBlock* pairs, TriangleDistanceBlock* out, std::size_t count,
                        TriangleSimd simd) noexcept {
  if (simd == TriangleSimd::Best) simd = triangle_simd_best();
#ifdef GJKDEM_HAVE_WIDE_PATHS
  if (simd == TriangleSimd::Avx512) return run_blocks_avx512(pairs, out, count);
  if (simd == TriangleSimd::Avx2) return run_blocks_avx2(pairs, out, count);
#endif
  run_blocks_sse2(pairs, out, count);
}

void triangle_distances(const TrianglePairs& pairs, std::vector<TriangleDistanceBlock>& out, TriangleSimd simd) {
  out.resize(pairs.blocks.size());
  triangle_distances(pairs.blocks.data(), out.data(), pairs.blocks.size(), simd);
}

TriangleContact triangle_contact(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, const Vec3& e,
                                 const Vec3& f, Real rho) noexcept {
  // One lane of the same kernel: a block would be 8x the work.
  TrianglePairBlock in;
  const Vec3 corners[2][3] = {{a, b, c}, {d, e, f}};
  for (int corner = 0; corner < 3; ++corner)
    for (int axis = 0; axis < 3; ++axis) {
      in.a[corner][axis][0] = corners[0][corner][axis];
      in.b[corner][axis][0] = corners[1][corner][axis];
    }
  TriangleDistanceBlock out;
  run_one_pair(in, out);
  TriangleContact r;
  r.distance = out.distance[0];
  r.witness_a = {out.witness_a[0][0], out.witness_a[1][0], out.witness_a[2][0]};
  r.witness_b = {out.witness_b[0][0], out.witness_b[1][0], out.witness_b[2][0]};
  r.contact = r.distance <= rho;
  r.status = r.distance > 0 ? GjkStatus::Separated : GjkStatus::Intersecting;
  if (r.distance > 0) r.normal = (r.witness_b - r.witness_a) / r.distance;
  return r;
}

}  // namespace gjkdem
