#include "gjkdem/shape/mass_properties.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <vector>
#include <stdexcept>

namespace gjkdem {
namespace {


Mat3 diagonal(Real x, Real y, Real z) {
  Mat3 m;
  m.row[0] = {x, 0, 0};
  m.row[1] = {0, y, 0};
  m.row[2] = {0, 0, z};
  return m;
}

// Inertia of a body with moments `axial` about unit axis u and `transverse`
// about any perpendicular axis: transverse I + (axial - transverse) u u^T.
Mat3 axisymmetric(const Vec3& u, Real axial, Real transverse) {
  Mat3 m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m.row[i][j] = (i == j ? transverse : 0) + (axial - transverse) * u[i] * u[j];
  return m;
}

MassProperties polytope(const PolytopeData& d) {
  if (d.triangles.empty()) throw std::invalid_argument("mass_properties: a flat polytope has no volume");
  return closed_surface_inertia(d.vertices, d.triangles, d.volume, d.centroid);
}

MassProperties superellipsoid(const Superellipsoid& s) {
  const Real a1 = s.radii.x, a2 = s.radii.y, a3 = s.radii.z, e1 = s.e1, e2 = s.e2;
  const Real k = a1 * a2 * a3 * e1 * e2;
  const Real volume = 2 * k * std::beta(e1 / 2 + 1, e1) * std::beta(e2 / 2, e2 / 2);
  // Second moments: J_xx = int x^2, J_zz = int z^2 (J_yy by symmetry with a2).
  const Real jx = k / 2 * a1 * a1 * std::beta(3 * e2 / 2, e2 / 2) * std::beta(e1 / 2, 2 * e1 + 1);
  const Real jy = k / 2 * a2 * a2 * std::beta(3 * e2 / 2, e2 / 2) * std::beta(e1 / 2, 2 * e1 + 1);
  const Real jz = 2 * k * a3 * a3 * std::beta(e2 / 2, e2 / 2 + 1) * std::beta(3 * e1 / 2, e1 + 1);
  return {volume, {}, diagonal(jy + jz, jx + jz, jx + jy)};
}

}  // namespace

MassProperties mass_properties(const Shape& shape) {
  const Real r = shape.margin;
  if (r > 0 && !std::holds_alternative<Point>(shape.core) && !std::holds_alternative<Segment>(shape.core))
    throw std::invalid_argument("mass_properties: margins are supported on spheres and capsules only");
  return std::visit(
      [r](const auto& c) -> MassProperties {
        using T = std::decay_t<decltype(c)>;
        if constexpr (std::is_same_v<T, Point>) {
          if (!(r > 0)) throw std::invalid_argument("mass_properties: a point has no volume");
          const Real v = 4 * kPi / 3 * r * r * r;
          return {v, {}, diagonal(0.4 * v * r * r, 0.4 * v * r * r, 0.4 * v * r * r)};
        } else if constexpr (std::is_same_v<T, Segment>) {
          if (!(r > 0)) throw std::invalid_argument("mass_properties: a segment has no volume");
          const Real len = length(c.b - c.a);
          const Vec3 u = len > 0 ? (c.b - c.a) / len : Vec3{0, 0, 1};
          const Real v_cyl = kPi * r * r * len, v_sph = 4 * kPi / 3 * r * r * r;
          // Cylinder plus two hemispheres (together a sphere) offset by len/2:
          // their transverse moment is v_sph (2 r^2 / 5 + len^2 / 4 + 3 r len / 8).
          const Real axial = v_cyl * r * r / 2 + v_sph * 0.4 * r * r;
          const Real transverse = v_cyl * (r * r / 4 + len * len / 12) + v_sph * (0.4 * r * r + len * len / 4 + 3 * r * len / 8);
          return {v_cyl + v_sph, (c.a + c.b) * 0.5, axisymmetric(u, axial, transverse)};
        } else if constexpr (std::is_same_v<T, Triangle>) {
          throw std::invalid_argument("mass_properties: a triangle has no volume");
        } else if constexpr (std::is_same_v<T, Box>) {
          const Vec3 h = c.half_extents;
          const Real v = 8 * h.x * h.y * h.z;
          if (!(v > 0)) throw std::invalid_argument("mass_properties: a flat box has no volume");
          return {v, {}, diagonal(v / 3 * (h.y * h.y + h.z * h.z), v / 3 * (h.x * h.x + h.z * h.z), v / 3 * (h.x * h.x + h.y * h.y))};
        } else if constexpr (std::is_same_v<T, Ellipsoid>) {
          const Vec3 a = c.radii;
          const Real v = 4 * kPi / 3 * a.x * a.y * a.z;
          return {v, {}, diagonal(v / 5 * (a.y * a.y + a.z * a.z), v / 5 * (a.x * a.x + a.z * a.z), v / 5 * (a.x * a.x + a.y * a.y))};
        } else if constexpr (std::is_same_v<T, Cylinder>) {
          const Real h = c.half_height, rr = c.radius;
          const Real v = kPi * rr * rr * 2 * h;
          return {v, {}, axisymmetric({0, 0, 1}, v * rr * rr / 2, v * (rr * rr / 4 + h * h / 3))};
        } else if constexpr (std::is_same_v<T, Cone>) {
          const Real height = 2 * c.half_height, rr = c.radius;
          const Real v = kPi * rr * rr * height / 3;
          // Centroid a quarter of the height above the base (base at z = -half_height).
          return {v, {0, 0, -c.half_height + height / 4},
                  axisymmetric({0, 0, 1}, 0.3 * v * rr * rr, v * (3 * rr * rr / 20 + 3 * height * height / 80))};
        } else if constexpr (std::is_same_v<T, Superellipsoid>) {
          return superellipsoid(c);
        } else {
          return polytope(*c.data);
        }
      },
      shape.core);
}

MassProperties mass_properties(std::span<const PlacedShape> parts) {
  std::vector<MassProperties> each;
  std::vector<Transform> poses;
  for (const PlacedShape& p : parts) each.push_back(mass_properties(p.shape)), poses.push_back(p.pose);
  return union_mass_properties(each, poses);
}

MassProperties union_mass_properties(std::span<const MassProperties> each, std::span<const Transform> poses) {
  MassProperties out;
  for (std::size_t k = 0; k < each.size(); ++k) {
    out.volume += each[k].volume;
    out.centroid += apply(poses[k], each[k].centroid) * each[k].volume;
  }
  if (out.volume > 0) out.centroid = out.centroid / out.volume;
  Real inertia[3][3] = {};
  for (std::size_t k = 0; k < each.size(); ++k) {
    const Mat3& r = poses[k].rotation;
    const Mat3 turned = r * each[k].inertia * transpose(r);  // about the part's centroid, compound axes
    const Vec3 d = apply(poses[k], each[k].centroid) - out.centroid;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        inertia[i][j] += turned.row[i][j] + each[k].volume * ((i == j ? dot(d, d) : 0) - d[i] * d[j]);
  }
  for (int i = 0; i < 3; ++i) out.inertia.row[i] = {inertia[i][0], inertia[i][1], inertia[i][2]};
  return out;
}

PrincipalAxes principal_axes(const Mat3& inertia) {
  Eigen::Matrix3d m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m(i, j) = 0.5 * (inertia.row[i][j] + inertia.row[j][i]);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(m);
  Eigen::Matrix3d v = solver.eigenvectors();  // columns, ascending eigenvalues
  if (v.determinant() < 0) v.col(2) = -v.col(2);
  const Eigen::Quaterniond q(v);
  PrincipalAxes p;
  p.moments = {solver.eigenvalues()(0), solver.eigenvalues()(1), solver.eigenvalues()(2)};
  p.rotation = normalized(Quat{q.w(), q.x(), q.y(), q.z()});
  return p;
}

MassProperties closed_surface_inertia(std::span<const Vec3> vertices,
                                      std::span<const std::array<std::uint32_t, 3>> triangles, Real volume,
                                      const Vec3& centroid) {
  // Second moments by tetrahedra (centroid, a, b, c): the covariance of one is
  // det/120 (a a^T + b b^T + c c^T + s s^T), s = a + b + c; inertia = tr(C) I - C.
  Real c[3][3] = {};
  for (const auto& t : triangles) {
    const Vec3 a = vertices[t[0]] - centroid, b = vertices[t[1]] - centroid, e = vertices[t[2]] - centroid;
    const Real det = dot(a, cross(b, e));
    const Vec3 s = a + b + e;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) c[i][j] += det / 120 * (a[i] * a[j] + b[i] * b[j] + e[i] * e[j] + s[i] * s[j]);
  }
  MassProperties m{volume, centroid, {}};
  const Real tr = c[0][0] + c[1][1] + c[2][2];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m.inertia.row[i][j] = (i == j ? tr : 0) - c[i][j];
  return m;
}

}  // namespace gjkdem
