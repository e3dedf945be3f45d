#include "convert.hpp"

#include <cmath>

#include "gjkdem/tolerances.hpp"

namespace gjkdem::py_bind {

void fail(const std::string& what, const std::string& message) { throw py::value_error(what + ": " + message); }

namespace {

std::string shape_text(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t k = 0; k < a.ndim(); ++k) s += (k ? ", " : "") + std::to_string(a.shape(k));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

py::array_t<double, py::array::c_style | py::array::forcecast> numbers(const py::handle& value, const std::string& what) {
  if (value.is_none()) fail(what, "expected numbers, got None");
  try {
    return py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
  } catch (const py::error_already_set&) {
  }
  fail(what, "expected numbers");
}

std::vector<double> fixed_numbers(const py::handle& value, py::ssize_t count, const std::string& what) {
  const auto a = numbers(value, what);
  if (!a) fail(what, "expected " + std::to_string(count) + " numbers");
  if (a.ndim() != 1 || a.shape(0) != count)
    fail(what, "expected " + std::to_string(count) + " numbers, got an array of shape " + shape_text(a));
  std::vector<double> out(a.data(), a.data() + count);
  for (double x : out)
    if (!std::isfinite(x)) fail(what, "NaN or infinite number");
  return out;
}

// Rows are read by the thousand: a row's name is made only for a message.
std::string row_name(const std::string& what, std::ptrdiff_t row) {
  return row < 0 ? what : what + "[" + std::to_string(row) + "]";
}

}  // namespace

Quat quat_from_row(const double* q, const std::string& what, std::ptrdiff_t row) {
  for (int k = 0; k < 4; ++k)
    if (!std::isfinite(q[k])) fail(row_name(what, row), "NaN or infinite number");
  const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (!(std::fabs(norm - 1) <= kUnitQuaternionTol))
    fail(row_name(what, row), "quaternion [w, x, y, z] must be unit (norm " + std::to_string(norm) + ")");
  return {q[0] / norm, q[1] / norm, q[2] / norm, q[3] / norm};
}

Vec3 to_vec3(const py::handle& value, const std::string& what) {
  const std::vector<double> v = fixed_numbers(value, 3, what);
  return {v[0], v[1], v[2]};
}

Quat to_quat(const py::handle& value, const std::string& what) {
  return quat_from_row(fixed_numbers(value, 4, what).data(), what);
}

Transform pose_from_row(const double* r, const std::string& what, std::ptrdiff_t row) {
  for (int k = 0; k < 3; ++k) {
    if (!std::isfinite(r[k])) fail(row_name(what, row), "NaN or infinite number");
    if (std::fabs(r[k]) > kMaxCoordinate)  // as the query format refuses such a coordinate
      fail(row_name(what, row), "a position outside the supported range [-1e100, 1e100]");
  }
  return Transform::from({r[0], r[1], r[2]}, quat_from_row(r + 3, what, row));
}

Transform to_pose(const py::handle& value, const std::string& what) {
  if (value.is_none()) return Transform::identity();
  const std::vector<double> p = fixed_numbers(value, 7, what + " [x, y, z, qw, qx, qy, qz]");
  return pose_from_row(p.data(), what);
}

py::array_t<double, py::array::c_style | py::array::forcecast> to_matrix(const py::handle& value, py::ssize_t cols,
                                                                          const std::string& what) {
  auto a = numbers(value, what);
  if (!a) fail(what, "expected an array of shape (N, " + std::to_string(cols) + ")");
  if (a.ndim() != 2 || a.shape(1) != cols)
    fail(what, "expected an array of shape (N, " + std::to_string(cols) + "), got " + shape_text(a));
  return a;
}

py::array_t<double> from_vec3(const Vec3& v) {
  py::array_t<double> a(3);
  double* p = a.mutable_data();
  p[0] = v.x, p[1] = v.y, p[2] = v.z;
  return a;
}

const Shape& convex_of(const PyShape& s, const char* what) {
  if (s.compound())
    fail(what, "a compound is for worlds (WorldBuilder); queries take one convex shape (query its parts one by one)");
  return s.shape;
}

// A region given once: lo and hi (a box), cylinder={base, axis, radius,
// height} or sphere={centre, radius}; the box into lo_out, hi_out.
std::optional<dem::RoundRegion> region_arg(const char* who, const py::object& lo, const py::object& hi,
                                           const py::object& cylinder, const py::object& sphere, Vec3& lo_out,
                                           Vec3& hi_out) {
  const int given = !lo.is_none() + !cylinder.is_none() + !sphere.is_none();
  if (given != 1 || lo.is_none() != hi.is_none())
    fail(who, "give the region once: lo and hi (a box), cylinder or sphere");
  if (!lo.is_none()) {
    lo_out = to_vec3(lo, "lo"), hi_out = to_vec3(hi, "hi");
    return std::nullopt;
  }
  if (!cylinder.is_none()) {
    const py::dict c = cylinder.cast<py::dict>();
    for (const char* key : {"radius", "height"})
      if (!c.contains(key)) fail("cylinder", std::string("needs '") + key + "'");
    return dem::RoundRegion{.kind = dem::RoundRegion::Kind::Cylinder,
                            .base = c.contains("base") ? to_vec3(c["base"], "cylinder base") : Vec3{},
                            .axis = c.contains("axis") ? to_vec3(c["axis"], "cylinder axis") : Vec3{0, 0, 1},
                            .radius = c["radius"].cast<double>(),
                            .height = c["height"].cast<double>()};
  }
  const py::dict c = sphere.cast<py::dict>();
  for (const char* key : {"centre", "radius"})
    if (!c.contains(key)) fail("sphere", std::string("needs '") + key + "'");
  return dem::RoundRegion{.kind = dem::RoundRegion::Kind::Ball,
                          .base = to_vec3(c["centre"], "sphere centre"),
                          .radius = c["radius"].cast<double>()};
}

TriangleArrays triangles_from_arrays(const py::handle& vertices, const py::handle& triangles) {
  const auto v = to_matrix(vertices, 3, "vertices");
  const auto t = to_matrix(triangles, 3, "triangles");
  std::vector<Vec3> points(static_cast<std::size_t>(v.shape(0)));
  for (py::ssize_t i = 0; i < v.shape(0); ++i) {
    const double* row = v.data(i, 0);
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(row[k])) fail("vertices[" + std::to_string(i) + "]", "must be finite numbers");
    points[static_cast<std::size_t>(i)] = {row[0], row[1], row[2]};
  }
  std::vector<std::array<std::uint32_t, 3>> corners(static_cast<std::size_t>(t.shape(0)));
  for (py::ssize_t i = 0; i < t.shape(0); ++i)
    for (int k = 0; k < 3; ++k) {
      const double x = *t.data(i, k);
      if (!(x >= 0 && x < static_cast<double>(points.size()) && x == std::floor(x)))
        fail("triangles[" + std::to_string(i) + "]",
             "must hold indices of vertices (integers from 0 to " + std::to_string(points.size()) + " - 1)");
      corners[static_cast<std::size_t>(i)][k] = static_cast<std::uint32_t>(x);
    }
  return {std::move(points), std::move(corners)};
}


}  // namespace gjkdem::py_bind
