// The closed-form triangle-pair kernel over a lane type V, included by
// triangle_contact.cpp once per instruction set (inside a namespace each,
// under #pragma GCC target for AVX2 and AVX-512, with
// GJKDEM_TRIANGLE_KERNEL_WIDTH the widest vector it may use), so that every
// helper is compiled for the instruction set of the loop that inlines it. No
// include guard on purpose.
//
// Every lane runs the same IEEE operations in the same order, without fused
// multiply-adds, so all widths give the same bits. No branches: every
// candidate is computed and kept or dropped by a select.

template <class V>
constexpr int kWidth = sizeof(V) / sizeof(double);

template <class V>
GJKDEM_LANE_INLINE V splat(double x) {
  if constexpr (std::is_same_v<V, double>) return x;
  else return V{} + x;
}
template <class V>
GJKDEM_LANE_INLINE V load(const double* p) {
  V v;
  std::memcpy(&v, p, sizeof(V));
  return v;
}
template <class V>
GJKDEM_LANE_INLINE void store(double* p, V v) {
  std::memcpy(p, &v, sizeof(V));
}
// m ? a : b lane by lane (m: a comparison's result).
template <class M, class V>
GJKDEM_LANE_INLINE V pick(M m, V a, V b) {
  return m ? a : b;
}
// Least and greatest, as minpd and maxpd compute them (b where either is
// NaN; inputs are finite here). A select takes up to three instructions, these
// one; GCC makes the generic form minpd only in simple contexts.
template <class V>
GJKDEM_LANE_INLINE V lane_min(V a, V b) {
  return a < b ? a : b;
}
template <class V>
GJKDEM_LANE_INLINE V lane_max(V a, V b) {
  return a > b ? a : b;
}
#if defined(__x86_64__)
GJKDEM_LANE_INLINE V2 lane_min(V2 a, V2 b) { return _mm_min_pd(a, b); }
GJKDEM_LANE_INLINE V2 lane_max(V2 a, V2 b) { return _mm_max_pd(a, b); }
#if GJKDEM_TRIANGLE_KERNEL_WIDTH >= 4
GJKDEM_LANE_INLINE V4 lane_min(V4 a, V4 b) { return _mm256_min_pd(a, b); }
GJKDEM_LANE_INLINE V4 lane_max(V4 a, V4 b) { return _mm256_max_pd(a, b); }
#endif
// 8 lanes (AVX-512) take the generic form: a compare into a mask register
// and a masked move, as cheap.
#endif

template <class V>
GJKDEM_LANE_INLINE V clamp01(V x) {
  return lane_min(lane_max(x, splat<V>(0)), splat<V>(1));
}

template <class V>
struct P3 {
  V x, y, z;
};
template <class V>
GJKDEM_LANE_INLINE P3<V> operator+(const P3<V>& a, const P3<V>& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class V>
GJKDEM_LANE_INLINE P3<V> operator-(const P3<V>& a, const P3<V>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class V>
GJKDEM_LANE_INLINE P3<V> operator*(const P3<V>& a, V s) {
  return {a.x * s, a.y * s, a.z * s};
}
template <class V>
GJKDEM_LANE_INLINE V dot(const P3<V>& a, const P3<V>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class V>
GJKDEM_LANE_INLINE P3<V> cross(const P3<V>& a, const P3<V>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class M, class V>
GJKDEM_LANE_INLINE P3<V> pick(M m, const P3<V>& a, const P3<V>& b) {
  return {pick(m, a.x, b.x), pick(m, a.y, b.y), pick(m, a.z, b.z)};
}
// 1/x, or 0 where x is 0 (a degenerate edge or triangle: its candidates then
// reduce to those of its points and edges, which the others cover).
template <class V>
GJKDEM_LANE_INLINE V inverse_or_zero(V x) {
  return pick(x > splat<V>(0), splat<V>(1) / pick(x > splat<V>(0), x, splat<V>(1)), splat<V>(0));
}

// One triangle's derived quantities, in the pair's local frame.
template <class V>
struct Tri {
  P3<V> p[3];      // corners
  P3<V> e[3];      // edges p[k] -> p[k+1]
  V ee[3];         // |e[k]|^2
  V ee_inv[3];     // 1 / |e[k]|^2 (0 for a point edge)
  P3<V> n;         // (p1 - p0) x (p2 - p0)
  V nn_inv;        // 1 / |n|^2 (0 for a flat triangle)
  P3<V> inward[3]; // n x e[k]: points into the triangle from edge k
};

template <class V>
GJKDEM_LANE_INLINE Tri<V> make_tri(const P3<V> (&p)[3]) {
  Tri<V> t;
  for (int k = 0; k < 3; ++k) t.p[k] = p[k];
  for (int k = 0; k < 3; ++k) t.e[k] = p[(k + 1) % 3] - p[k];
  for (int k = 0; k < 3; ++k) t.ee[k] = dot(t.e[k], t.e[k]);
  for (int k = 0; k < 3; ++k) t.ee_inv[k] = inverse_or_zero(t.ee[k]);
  t.n = cross(t.e[0], p[2] - p[0]);
  t.nn_inv = inverse_or_zero(dot(t.n, t.n));
  for (int k = 0; k < 3; ++k) t.inward[k] = cross(t.n, t.e[k]);
  return t;
}

// The best candidate so far: squared distance and its two points.
template <class V>
struct Best {
  V d2;
  P3<V> pa, pb;

  GJKDEM_LANE_INLINE void offer(V cand_d2, const P3<V>& a, const P3<V>& b) {
    const auto better = cand_d2 < d2;
    d2 = lane_min(cand_d2, d2);
    pa = pick(better, a, pa);
    pb = pick(better, b, pb);
  }
};

// Corners of `s` (signed plane values `h`, scaled by |t.n|) over the face of
// `t`: candidates where the corner projects inside; the inside tests' values
// `g` are returned for the edge-crossing test. `s_first` says which side
// `s` is, so that the points go to the right witness.
template <class V>
GJKDEM_LANE_INLINE void corners_over_face(const Tri<V>& s, const Tri<V>& t, const V (&h)[3], V (&g)[3][3],
                                          bool s_first, Best<V>& best) {
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < 3; ++k) g[i][k] = dot(s.p[i] - t.p[k], t.inward[k]);
    const auto inside = (g[i][0] >= splat<V>(0)) & (g[i][1] >= splat<V>(0)) & (g[i][2] >= splat<V>(0)) &
                        (t.nn_inv > splat<V>(0));
    const V d2 = pick(inside, h[i] * h[i] * t.nn_inv, splat<V>(std::numeric_limits<double>::infinity()));
    const P3<V> foot = s.p[i] - t.n * (h[i] * t.nn_inv);
    if (s_first) best.offer(d2, s.p[i], foot);
    else best.offer(d2, foot, s.p[i]);
  }
}

// Edges of `s` that cross the plane of `t` strictly inside `t`: such a pair
// intersects. The crossing of edge i -> j is (h_i p_j - h_j p_i)/(h_i - h_j);
// its inside values are (h_i g_j - h_j g_i)/(h_i - h_j), whose denominator has
// the sign of h_i, so no division is needed to test it. The last crossing
// found is kept (its edge's end values) for the witness.
template <class V, class M>
GJKDEM_LANE_INLINE void edges_through_face(const Tri<V>& s, const V (&h)[3], const V (&g)[3][3], M& hit,
                                           P3<V>& xi, P3<V>& xj, V& hi, V& hj) {
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    auto crosses = h[i] * h[j] < splat<V>(0);
    for (int k = 0; k < 3; ++k) crosses = crosses & ((h[i] * g[j][k] - h[j] * g[i][k]) * h[i] >= splat<V>(0));
    hit = hit | crosses;
    xi = pick(crosses, s.p[i], xi);
    xj = pick(crosses, s.p[j], xj);
    hi = pick(crosses, h[i], hi);
    hj = pick(crosses, h[j], hj);
  }
}

// Closest points of edge k of `s` and edge l of `t` (Ericson 5.1.9, with
// selects): the interior stationary point where the edges are not parallel,
// clamped, then re-projected from the clamped end.
template <class V>
GJKDEM_LANE_INLINE void edge_edge(const Tri<V>& s, int k, const Tri<V>& t, int l, Best<V>& best) {
  const P3<V>& d1 = s.e[k];
  const P3<V>& d2 = t.e[l];
  const P3<V> r = s.p[k] - t.p[l];
  const V aa = s.ee[k], ee = t.ee[l], b = dot(d1, d2), c = dot(d1, r), f = dot(d2, r);
  const V denom = aa * ee - b * b;
  const auto skew = denom > splat<V>(0);
  const V s_skew = (b * f - c * ee) / pick(skew, denom, splat<V>(1));
  V u = clamp01(pick(skew, s_skew, -c * s.ee_inv[k]));
  const V v_free = (b * u + f) * t.ee_inv[l];
  const V v = clamp01(v_free);
  u = pick(v != v_free, clamp01((v * b - c) * s.ee_inv[k]), u);
  const P3<V> pa = s.p[k] + d1 * u, pb = t.p[l] + d2 * v;
  const P3<V> gap = pa - pb;
  best.offer(dot(gap, gap), pa, pb);
}

// Lanes [0, W) of the block at `lane0`.
template <class V>
GJKDEM_LANE_INLINE void run_lanes(const TrianglePairBlock& in, TriangleDistanceBlock& out, int lane0) {
  const auto corner = [&](const Real(&side)[3][3][kTriangleLanes], int c) {
    return P3<V>{load<V>(&side[c][0][lane0]), load<V>(&side[c][1][lane0]), load<V>(&side[c][2][lane0])};
  };
  // The first corner of ABC is the local origin: round-off then follows the
  // triangles' size and gap, not their distance from the world origin...
  const P3<V> origin = corner(in.a, 0);
  P3<V> pa[3] = {corner(in.a, 0) - origin, corner(in.a, 1) - origin, corner(in.a, 2) - origin};
  P3<V> pb[3] = {corner(in.b, 0) - origin, corner(in.b, 1) - origin, corner(in.b, 2) - origin};
  // ...and the pair's extent is the unit: the candidates multiply up to four
  // lengths, which would overflow or underflow for triangles far from size 1
  // (1e-80 or 1e80 m); in units of the extent they cannot.
  V extent = splat<V>(0);
  for (const P3<V>* side : {pa, pb})
    for (int k = 0; k < 3; ++k)
      extent = lane_max(extent, lane_max(lane_max(lane_max(side[k].x, -side[k].x), lane_max(side[k].y, -side[k].y)),
                                         lane_max(side[k].z, -side[k].z)));
  const V unit = pick(extent > splat<V>(0), extent, splat<V>(1));
  const V per_unit = splat<V>(1) / unit;
  for (int k = 0; k < 3; ++k) pa[k] = pa[k] * per_unit, pb[k] = pb[k] * per_unit;
  const Tri<V> ta = make_tri(pa), tb = make_tri(pb);

  V ha[3], hb[3];  // corners' plane values against the other triangle
  for (int i = 0; i < 3; ++i) ha[i] = dot(ta.p[i] - tb.p[0], tb.n);
  for (int i = 0; i < 3; ++i) hb[i] = dot(tb.p[i] - ta.p[0], ta.n);

  Best<V> best{splat<V>(std::numeric_limits<double>::infinity()), ta.p[0], tb.p[0]};
  V ga[3][3], gb[3][3];
  corners_over_face(ta, tb, ha, ga, true, best);
  corners_over_face(tb, ta, hb, gb, false, best);
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l) edge_edge(ta, k, tb, l, best);

  auto hit = splat<V>(1) < splat<V>(0);  // all false
  P3<V> xi = ta.p[0], xj = ta.p[0];
  V hi = splat<V>(1), hj = splat<V>(0);
  edges_through_face(ta, ha, ga, hit, xi, xj, hi, hj);
  edges_through_face(tb, hb, gb, hit, xi, xj, hi, hj);
  const P3<V> cross_point = (xj * hi - xi * hj) * (splat<V>(1) / (hi - hj));

  const V d2 = pick(hit, splat<V>(0), best.d2);
  const P3<V> wa = pick(hit, cross_point, best.pa) * unit + origin;
  const P3<V> wb = pick(hit, cross_point, best.pb) * unit + origin;
  double d2_lanes[kWidth<V>], unit_lanes[kWidth<V>];
  store(d2_lanes, d2);
  store(unit_lanes, unit);
  for (int w = 0; w < kWidth<V>; ++w) out.distance[lane0 + w] = std::sqrt(d2_lanes[w]) * unit_lanes[w];
  store(&out.witness_a[0][lane0], wa.x);
  store(&out.witness_a[1][lane0], wa.y);
  store(&out.witness_a[2][lane0], wa.z);
  store(&out.witness_b[0][lane0], wb.x);
  store(&out.witness_b[1][lane0], wb.y);
  store(&out.witness_b[2][lane0], wb.z);
}

template <class V>
GJKDEM_LANE_INLINE void run_blocks(const TrianglePairBlock* in, TriangleDistanceBlock* out, std::size_t count) {
  for (std::size_t i = 0; i < count; ++i)
    for (int lane0 = 0; lane0 < kTriangleLanes; lane0 += kWidth<V>) run_lanes<V>(in[i], out[i], lane0);
}
