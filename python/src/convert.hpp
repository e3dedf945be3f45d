#pragma once
// Python values in and out: the checks every binding makes on what it is
// given (shapes of arrays, finite numbers, unit quaternions), with the
// messages the user sees as ValueError. Nothing here holds state.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "gjkdem/dem/body.hpp"
#include "gjkdem/dem/round_region.hpp"
#include "gjkdem/math/transform.hpp"
#include "gjkdem/shape/shape.hpp"

namespace gjkdem::py_bind {

namespace py = pybind11;

/// A shape as Python holds it: the core in a frame centred on it, placed in
/// the frame the user gave it in (so a polytope keeps its coordinates).
struct PyShape {
  Shape shape;       ///< a compound's hull
  Transform offset;  ///< shape frame -> the user's frame
  std::string type;
  std::vector<PlacedShape> parts;  ///< a compound's convex parts (empty otherwise)
  std::vector<dem::PlacedSurface> surface_parts;  ///< a compound's surfaces, parts after `parts`
  bool compound() const noexcept { return !parts.empty() || !surface_parts.empty(); }
};

/// The convex shape of `s`; raises ValueError for a compound (queries take
/// convex shapes: a compound's hull would be a silent wrong answer).
const Shape& convex_of(const PyShape& s, const char* what);

/// Raises ValueError("what: message").
[[noreturn]] void fail(const std::string& what, const std::string& message);

/// Three finite numbers.
Vec3 to_vec3(const py::handle& value, const std::string& what);

/// A region given once: lo and hi (a box, into lo_out and hi_out),
/// cylinder={base, axis, radius, height} or sphere={centre, radius}
/// (ValueError naming `who` otherwise).
std::optional<dem::RoundRegion> region_arg(const char* who, const py::object& lo, const py::object& hi,
                                           const py::object& cylinder, const py::object& sphere, Vec3& lo_out,
                                           Vec3& hi_out);
/// A unit quaternion [w, x, y, z] (to kUnitQuaternionTol), normalized.
Quat to_quat(const py::handle& value, const std::string& what);
/// None (identity) or 7 finite numbers [x, y, z, qw, qx, qy, qz] with a unit quaternion.
Transform to_pose(const py::handle& value, const std::string& what);
/// A unit quaternion from 4 numbers [w, x, y, z] (finite, unit to
/// kUnitQuaternionTol), normalized; messages name it `what`, or `what[row]`.
Quat quat_from_row(const double* values, const std::string& what, std::ptrdiff_t row = -1);
/// A pose from a row of 7 numbers (checked as to_pose); messages name it
/// `what`, or `what[row]` for row >= 0.
Transform pose_from_row(const double* values, const std::string& what, std::ptrdiff_t row = -1);

/// An (N, cols) C-ordered float64 array (a copy only when the input is not one).
py::array_t<double, py::array::c_style | py::array::forcecast> to_matrix(const py::handle& value, py::ssize_t cols,
                                                                          const std::string& what);

py::array_t<double> from_vec3(const Vec3& v);

/// Vertices (N, 3), finite, and triangles (M, 3) of indices into them: whole
/// numbers from 0 to N - 1 (a float index is refused, not truncated), as
/// every binding taking a triangle mesh reads them (surfaces, shells, mesh
/// walls); the one index rule (triangle_index_problem) is the library's.
struct TriangleArrays {
  std::vector<Vec3> points;
  std::vector<std::array<std::uint32_t, 3>> corners;
};
TriangleArrays triangles_from_arrays(const py::handle& vertices, const py::handle& triangles);

}  // namespace gjkdem::py_bind
