#include "gjkdem/shape/polytope.hpp"

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <new>
#include <stdexcept>
#include <type_traits>

#include "gjkdem/shape/convex_hull.hpp"
#include "gjkdem/shape/hull_surface_slot.hpp"
#include "gjkdem/tolerances.hpp"

namespace gjkdem {
namespace {

// The arrays of a polytope while they are being built.
struct Arrays {
  std::vector<Real> soa;
  std::vector<Vec3> vertices;
  std::vector<std::uint32_t> adj_begin, adj, start;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<std::uint32_t> facet_begin, facet_vertices;
  std::vector<Vec3> facet_normals;
};

constexpr std::size_t kBlockAlign = 64;  // a cache line

std::size_t align_up(std::size_t n, std::size_t a) { return (n + a - 1) / a * a; }

// Copies the header and every array into one block (header first, arrays in
// the order of Arrays), owned by the returned pointer, with an empty surface
// slot for a big solid hull.
std::shared_ptr<const PolytopeData> pack(const PolytopeData& header, const Arrays& a) {
  std::size_t size = align_up(sizeof(PolytopeData), kBlockAlign);
  const auto place = [&](const auto& v) {
    using T = typename std::decay_t<decltype(v)>::value_type;
    size = align_up(size, alignof(T));
    const std::size_t at = size;
    size += v.size() * sizeof(T);
    return at;
  };
  const std::size_t at[] = {place(a.soa),       place(a.vertices),    place(a.adj_begin),
                            place(a.adj),       place(a.start),       place(a.triangles),
                            place(a.facet_begin), place(a.facet_vertices), place(a.facet_normals)};
  auto* block = static_cast<std::byte*>(::operator new(size, std::align_val_t{kBlockAlign}));
  auto* d = new (block) PolytopeData(header);
  const auto copy = [&](const auto& v, std::size_t offset) {
    using T = typename std::decay_t<decltype(v)>::value_type;
    T* out = reinterpret_cast<T*>(block + offset);
    std::uninitialized_copy(v.begin(), v.end(), out);
    return std::span<const T>(out, v.size());
  };
  d->soa = copy(a.soa, at[0]);
  d->vertices = copy(a.vertices, at[1]);
  d->adj_begin = copy(a.adj_begin, at[2]);
  d->adj = copy(a.adj, at[3]);
  d->start = copy(a.start, at[4]);
  d->triangles = copy(a.triangles, at[5]);
  d->facet_begin = copy(a.facet_begin, at[6]);
  d->facet_vertices = copy(a.facet_vertices, at[7]);
  d->facet_normals = copy(a.facet_normals, at[8]);
  static_assert(std::is_trivially_destructible_v<PolytopeData>);
  const auto release = [](const PolytopeData* p) {
    delete p->surface_slot;
    ::operator delete(const_cast<PolytopeData*>(p), std::align_val_t{kBlockAlign});
  };
  std::shared_ptr<const PolytopeData> owned(d, release);
  if (a.triangles.size() >= static_cast<std::size_t>(kSurfaceRouteMinTriangles)) d->surface_slot = new HullSurfaceSlot;
  return owned;
}

}  // namespace

Polytope make_polytope(std::span<const Vec3> points) {
  if (points.empty()) throw std::invalid_argument("polytope needs at least one point");
  for (const Vec3& q : points)
    if (!is_finite(q)) throw std::invalid_argument("polytope point is not finite");
  ConvexHull hull = convex_hull(points);
  PolytopeData header;
  Arrays a;  // the arrays; the scalars go in header
  a.vertices = std::move(hull.vertices);
  for (const Vec3& v : a.vertices) header.radius = std::fmax(header.radius, length(v));
  const auto n = a.vertices.size();
  if (hull.dimension == HullDimension::Solid) {
    // Volume and centroid by the divergence theorem over tetrahedra from the
    // bounding-box centre (the local origin for the query format's shapes).
    Real vol6 = 0;
    Vec3 moment;
    for (const auto& t : hull.triangles) {
      const Vec3 &p0 = a.vertices[t[0]], &p1 = a.vertices[t[1]], &p2 = a.vertices[t[2]];
      const Real v6 = dot(p0, cross(p1, p2));
      vol6 += v6;
      moment += (p0 + p1 + p2) * (v6 / 4);
      a.triangles.push_back({static_cast<std::uint32_t>(t[0]), static_cast<std::uint32_t>(t[1]),
                                 static_cast<std::uint32_t>(t[2])});
    }
    header.volume = vol6 / 6;
    a.facet_normals = hull.facet_normals;
    a.facet_begin.push_back(0);
    for (const auto& facet : hull.facets) {
      for (int i : facet) a.facet_vertices.push_back(static_cast<std::uint32_t>(i));
      a.facet_begin.push_back(static_cast<std::uint32_t>(a.facet_vertices.size()));
    }
    header.centroid = vol6 > 0 ? moment / vol6 : Vec3{};
  } else {
    for (const Vec3& v : a.vertices) header.centroid += v / static_cast<Real>(n);
  }
  header.soa_stride = static_cast<int>((n + 3) / 4 * 4);  // whole steps of the 4-wide scan
  a.soa.resize(3 * static_cast<std::size_t>(header.soa_stride));
  for (int i = 0; i < header.soa_stride; ++i) {
    const Vec3& v = a.vertices[static_cast<std::size_t>(i) < n ? i : 0];
    a.soa[i] = v.x;
    a.soa[header.soa_stride + i] = v.y;
    a.soa[2 * header.soa_stride + i] = v.z;
  }
  if (hull.dimension == HullDimension::Solid && hull.manifold && n > static_cast<std::size_t>(kHillClimbMinVertices)) {
    std::vector<std::vector<std::uint32_t>> nbr(n);
    for (const auto& t : hull.triangles)
      for (int k = 0; k < 3; ++k) nbr[t[k]].push_back(static_cast<std::uint32_t>(t[(k + 1) % 3]));
    a.adj_begin.reserve(n + 1);
    a.adj_begin.push_back(0);
    for (const auto& list : nbr) {
      a.adj.insert(a.adj.end(), list.begin(), list.end());
      a.adj_begin.push_back(static_cast<std::uint32_t>(a.adj.size()));
    }
    // Start table: the exact support vertex of each cell's centre direction.
    constexpr int res = kSupportMapResolution;
    a.start.resize(6 * res * res);
    for (int face = 0; face < 6; ++face)
      for (int iu = 0; iu < res; ++iu)
        for (int iv = 0; iv < res; ++iv) {
          const int axis = face / 2;
          Vec3 d;
          d[axis] = face % 2 ? -1 : 1;
          d[(axis + 1) % 3] = (iu + Real(0.5)) * 2 / res - 1;
          d[(axis + 2) % 3] = (iv + Real(0.5)) * 2 / res - 1;
          std::uint32_t best = 0;
          for (std::uint32_t i = 1; i < n; ++i)
            if (dot(a.vertices[i], d) > dot(a.vertices[best], d)) best = i;
          a.start[detail::support_map_cell(d)] = best;
        }
  }
  return Polytope{pack(header, a)};
}

namespace detail {

#if defined(__x86_64__)
namespace {

// The 4-wide scan: lane k keeps the first maximum of vertices k, k + 4, ...
// and its index; the lanes' maxima then give the first vertex with the
// largest product, ties to the smaller index, as the 2-wide scan does. The
// products are the same sums in the same order (no fused multiply-add), so
// the vertex is the same bits on any processor.
__attribute__((target("avx2"))) int scan_avx2(const PolytopeData& s, const Vec3& d) noexcept {
  const Real* xs = s.soa.data();
  const Real* ys = xs + s.soa_stride;
  const Real* zs = ys + s.soa_stride;
  const int m = s.soa_stride;
  const __m256d dx = _mm256_set1_pd(d.x), dy = _mm256_set1_pd(d.y), dz = _mm256_set1_pd(d.z);
  __m256d best = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(_mm256_loadu_pd(xs), dx), _mm256_mul_pd(_mm256_loadu_pd(ys), dy)),
                               _mm256_mul_pd(_mm256_loadu_pd(zs), dz));
  __m256d index = _mm256_set_pd(3, 2, 1, 0);
  __m256d at = index;
  const __m256d four = _mm256_set1_pd(4);
  for (int i = 4; i < m; i += 4) {
    at = _mm256_add_pd(at, four);
    const __m256d t = _mm256_add_pd(
        _mm256_add_pd(_mm256_mul_pd(_mm256_loadu_pd(xs + i), dx), _mm256_mul_pd(_mm256_loadu_pd(ys + i), dy)),
        _mm256_mul_pd(_mm256_loadu_pd(zs + i), dz));
    const __m256d more = _mm256_cmp_pd(t, best, _CMP_GT_OQ);
    best = _mm256_blendv_pd(best, t, more);
    index = _mm256_blendv_pd(index, at, more);
  }
  alignas(32) double b[4], k[4];
  _mm256_store_pd(b, best);
  _mm256_store_pd(k, index);
  int lane = 0;
  for (int l = 1; l < 4; ++l)
    if (b[l] > b[lane] || (b[l] == b[lane] && k[l] < k[lane])) lane = l;
  return static_cast<int>(k[lane]);
}

}  // namespace
#endif

int scan_support_index_wide(const PolytopeData& s, const Vec3& d) noexcept {
#if defined(__x86_64__)
  if (__builtin_cpu_supports("avx2")) return scan_avx2(s, d);
#endif
  return scan_support_index_narrow(s, d);
}

}  // namespace detail

Real facet_distance(const PolytopeData& d, const Vec3& p) noexcept {
  Real most = -std::numeric_limits<Real>::infinity();
  for (std::size_t f = 0; f + 1 < d.facet_begin.size(); ++f)
    most = std::fmax(most, dot(d.facet_normals[f], p - d.vertices[d.facet_vertices[d.facet_begin[f]]]));
  return most;
}

}  // namespace gjkdem
