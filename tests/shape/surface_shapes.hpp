#pragma once
// Closed surfaces for tests: boxes and an L-shaped prism, as vertex and
// triangle lists (outward, counter-clockwise from outside).
#include <cmath>
#include <vector>

#include "gjkdem/shape/surface.hpp"

namespace gjkdem::test {

struct Mesh {
  std::vector<Vec3> vertices;
  std::vector<TriangleIndices> triangles;
};

/// A prism over a polygon (counter-clockwise in x, y) from z0 to z1; `cap`
/// triangulates the polygon (indices into it, counter-clockwise).
inline Mesh prism(const std::vector<std::pair<Real, Real>>& outline, const std::vector<TriangleIndices>& cap, Real z0,
                  Real z1) {
  Mesh m;
  const std::uint32_t n = static_cast<std::uint32_t>(outline.size());
  for (const auto& [x, y] : outline) m.vertices.push_back({x, y, z0});
  for (const auto& [x, y] : outline) m.vertices.push_back({x, y, z1});
  for (const TriangleIndices& t : cap) {
    m.triangles.push_back({t[0], t[2], t[1]});              // bottom, facing down
    m.triangles.push_back({t[0] + n, t[1] + n, t[2] + n});  // top
  }
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t j = (i + 1) % n;
    m.triangles.push_back({i, j, j + n});
    m.triangles.push_back({i, j + n, i + n});
  }
  return m;
}

inline Mesh box_surface(const Vec3& lo, const Vec3& hi) {
  return prism({{lo.x, lo.y}, {hi.x, lo.y}, {hi.x, hi.y}, {lo.x, hi.y}}, {{0, 1, 2}, {0, 2, 3}}, lo.z, hi.z);
}

/// The L of [0,2]x[0,1] and [0,1]x[0,2], from z = 0 to `height`.
inline Mesh l_prism(Real height) {
  return prism({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}, {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}}, 0, height);
}

/// The U of [0,3]x[0,1] and the arms [0,1]x[1,2] and [2,3]x[1,2], from z = 0 to `height`.
inline Mesh u_prism(Real height) {
  return prism({{0, 0}, {3, 0}, {3, 2}, {2, 2}, {2, 1}, {1, 1}, {1, 2}, {0, 2}},
               {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {0, 4, 5}, {0, 5, 7}, {5, 6, 7}}, 0, height);
}

/// A torus about the z axis: the circle of radius `major` in the xy-plane
/// swept by a tube of radius `minor`, `around` by `across` quads.
inline Mesh torus(Real major, Real minor, int around, int across) {
  Mesh m;
  const Real tau = 6.283185307179586;
  for (int i = 0; i < around; ++i)
    for (int j = 0; j < across; ++j) {
      const Real u = tau * i / around, v = tau * j / across;
      m.vertices.push_back({(major + minor * std::cos(v)) * std::cos(u), (major + minor * std::cos(v)) * std::sin(u),
                            minor * std::sin(v)});
    }
  const auto at = [&](int i, int j) { return static_cast<std::uint32_t>((i % around) * across + j % across); };
  for (int i = 0; i < around; ++i)
    for (int j = 0; j < across; ++j) {
      m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return m;
}

/// A bowl: the solid between two spheres about the origin (radii `inner` <
/// `outer`) below z = 0, closed by a flat rim; `around` by `down` quads per
/// sphere. Its hollow opens upward.
inline Mesh bowl(Real inner, Real outer, int around, int down) {
  Mesh m;
  const Real tau = 6.283185307179586;
  // Ring j (0 at the rim, down at the pole) of sphere r; poles shared.
  for (const Real r : {outer, inner}) {
    for (int j = 0; j < down; ++j)
      for (int i = 0; i < around; ++i) {
        const Real polar = tau / 4 * j / down, u = tau * i / around;  // from the rim (polar 0) to the pole
        m.vertices.push_back({r * std::cos(polar) * std::cos(u), r * std::cos(polar) * std::sin(u), -r * std::sin(polar)});
      }
    m.vertices.push_back({0, 0, -r});
  }
  const std::uint32_t per = static_cast<std::uint32_t>(around * down + 1);
  const auto at = [&](int sphere, int j, int i) {
    return j == down ? sphere * per + per - 1 : static_cast<std::uint32_t>(sphere * per + j * around + i % around);
  };
  for (int sphere = 0; sphere < 2; ++sphere)
    for (int j = 0; j < down; ++j)
      for (int i = 0; i < around; ++i) {
        // Outer faces point away from the centre, inner ones towards it.
        const std::uint32_t p = at(sphere, j, i), q = at(sphere, j, i + 1), r = at(sphere, j + 1, i + 1),
                            s = at(sphere, j + 1, i);
        if (j + 1 == down) {
          if (sphere == 0) m.triangles.push_back({p, r, q});
          else m.triangles.push_back({p, q, r});
        } else if (sphere == 0) {
          m.triangles.push_back({p, r, q});
          m.triangles.push_back({p, s, r});
        } else {
          m.triangles.push_back({p, q, r});
          m.triangles.push_back({p, r, s});
        }
      }
  for (int i = 0; i < around; ++i) {  // the rim, facing up
    const std::uint32_t o0 = at(0, 0, i), o1 = at(0, 0, i + 1), i0 = at(1, 0, i), i1 = at(1, 0, i + 1);
    m.triangles.push_back({o0, o1, i1});
    m.triangles.push_back({o0, i1, i0});
  }
  return m;
}

/// Adds b's triangles to a (b's vertices appended; with `weld`, b's
/// vertices equal to one of a's are taken as a's).
inline void append(Mesh& a, const Mesh& b, bool weld = false) {
  std::vector<std::uint32_t> index(b.vertices.size());
  for (std::size_t i = 0; i < b.vertices.size(); ++i) {
    index[i] = static_cast<std::uint32_t>(a.vertices.size());
    if (weld)
      for (std::uint32_t k = 0; k < a.vertices.size(); ++k)
        if (a.vertices[k] == b.vertices[i]) index[i] = k;
    if (index[i] == a.vertices.size()) a.vertices.push_back(b.vertices[i]);
  }
  for (const TriangleIndices& t : b.triangles) a.triangles.push_back({index[t[0]], index[t[1]], index[t[2]]});
}

inline Surface surface_of(const Mesh& m) { return make_surface(m.vertices, m.triangles); }

}  // namespace gjkdem::test
