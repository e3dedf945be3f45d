// Queries between two placed shapes, one pair at a time or in batches (an
// (N, 7) array of poses per side, or lists of shapes) computed with the GIL
// released and spread over threads. Poses are [x, y, z, qw, qx, qy, qz]:
// position and unit quaternion of the shape's frame in the world.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "bindings.hpp"
#include "gjkdem/collide/query.hpp"
#include "gjkdem/collide/triangle_contact.hpp"
#include "gjkdem/contact/overlap.hpp"

namespace gjkdem::py_bind {
namespace {

const char* gjk_status_name(GjkStatus s) {
  switch (s) {
    case GjkStatus::Separated: return "separated";
    case GjkStatus::Intersecting: return "intersecting";
    case GjkStatus::MaxIterations: return "max_iterations";
  }
  return "?";
}

const char* epa_status_name(EpaStatus s) {
  switch (s) {
    case EpaStatus::NotRun: return "not_run";
    case EpaStatus::Converged: return "converged";
    case EpaStatus::Touching: return "touching";
    case EpaStatus::Degenerate: return "degenerate";
    case EpaStatus::OutOfMemory: return "out_of_memory";
    case EpaStatus::MaxIterations: return "max_iterations";
  }
  return "?";
}

const char* overlap_status_name(OverlapStatus s) {
  switch (s) {
    case OverlapStatus::Empty: return "empty";
    case OverlapStatus::Overlapping: return "overlapping";
    case OverlapStatus::Unsupported: return "unsupported";
  }
  return "?";
}

Transform placed(const PyShape& s, const Transform& pose) { return compose(pose, s.offset); }

// Shapes packed for batches (gjkdem.ShapeSet).
struct ShapeSet {
  std::vector<Shape> shapes;
  std::vector<Transform> offsets;  // each shape's frame -> the user's
};

// One side of a batch: a shape for every pair (or one for all), and their
// poses. The shapes are the Python objects of a list, or a ShapeSet's
// contiguous arrays.
struct Side {
  std::vector<const PyShape*> shapes;  // one, or one per pair (a list)
  const ShapeSet* set = nullptr;       // or these
  std::vector<Transform> poses;        // one per pair, when `posed`
  bool posed = false;                  // poses were given (an (N, 7) array, N may be 0)
  // The Python objects behind `shapes` and `set`, held: a batch runs with
  // the GIL released, while another thread may empty the list it came from.
  std::vector<py::object> held;
  std::size_t size() const { return set ? set->shapes.size() : shapes.size(); }
  const Shape& shape(std::size_t k) const {
    const std::size_t i = size() == 1 ? 0 : k;
    return set ? set->shapes[i] : shapes[i]->shape;
  }
  Transform pose(std::size_t k) const {
    const std::size_t i = size() == 1 ? 0 : k;
    const Transform& offset = set ? set->offsets[i] : shapes[i]->offset;
    return posed ? compose(poses[k], offset) : offset;
  }
};

// The shape held by a Python object, or null. Lists of thousands of shapes
// are read per call, so exact gjkdem.Shape objects skip pybind11's type
// lookups (two hash-map searches each, about 150 ns).
const PyShape* shape_of(const py::handle& item) {
  static PyTypeObject* const exact = reinterpret_cast<PyTypeObject*>(py::type::of<PyShape>().ptr());
  if (Py_TYPE(item.ptr()) == exact)
    return static_cast<const PyShape*>(reinterpret_cast<py::detail::instance*>(item.ptr())->get_value_and_holder().value_ptr());
  if (!py::isinstance<PyShape>(item)) return nullptr;
  return &item.cast<const PyShape&>();
}

Side read_side(const py::handle& shapes, const py::handle& poses, const std::string& name) {
  Side s;
  if (py::isinstance<ShapeSet>(shapes)) {
    s.set = &shapes.cast<const ShapeSet&>();
    s.held.push_back(py::reinterpret_borrow<py::object>(shapes));
  } else if (const PyShape* one = shape_of(shapes)) {
    convex_of(*one, name.c_str());
    s.shapes.push_back(one);
    s.held.push_back(py::reinterpret_borrow<py::object>(shapes));
  } else {
    if (!PyList_Check(shapes.ptr()) && !PyTuple_Check(shapes.ptr()))
      fail(name, "expected a gjkdem.Shape, a list of them or a ShapeSet");
    const py::sequence items = py::reinterpret_borrow<py::sequence>(shapes);
    s.shapes.reserve(items.size());
    s.held.reserve(items.size());
    for (const auto& item : items) {
      const PyShape* shape = shape_of(item);
      if (!shape) fail(name, "expected a gjkdem.Shape or a list of them");
      convex_of(*shape, name.c_str());
      s.shapes.push_back(shape);
      s.held.push_back(py::object(item));
    }
    if (s.shapes.empty()) fail(name, "the list of shapes is empty");
  }
  if (!poses.is_none()) {
    const std::string what = "poses_" + name.substr(name.size() - 1);
    const auto rows = to_matrix(poses, 7, what);
    s.posed = true;
    s.poses.reserve(static_cast<std::size_t>(rows.shape(0)));
    for (py::ssize_t k = 0; k < rows.shape(0); ++k)
      s.poses.push_back(pose_from_row(rows.data(k, 0), what, k));
  }
  return s;
}

// The number of pairs both sides agree on.
std::size_t pair_count(const Side& a, const Side& b) {
  std::size_t n = 1;
  bool known = false;
  // Every list of shapes longer than one and every pose array says how many
  // pairs there are (an empty pose array: none).
  for (const auto& [given, count] : {std::pair{a.size() > 1, a.size()}, {a.posed, a.poses.size()},
                                    {b.size() > 1, b.size()}, {b.posed, b.poses.size()}}) {
    if (!given) continue;
    if (known && count != n)
      throw py::value_error("batch: the shape lists and pose arrays must have one entry per pair (got " +
                            std::to_string(n) + " and " + std::to_string(count) + ")");
    n = count, known = true;
  }
  if (!known) throw py::value_error("batch: give poses as (N, 7) arrays or shapes as lists to say how many pairs");
  return n;
}

int thread_count(int requested) {
  if (requested < 0) throw py::value_error("threads: must be >= 0 (0: every core)");
#ifdef _OPENMP
  return requested == 0 ? omp_get_max_threads() : requested;
#else
  return 1;
#endif
}

// Row k of an (N, 3) array, by its raw pointer (written with the GIL released).
void put(double* rows, std::size_t k, const Vec3& v) {
  double* p = rows + 3 * k;
  p[0] = v.x, p[1] = v.y, p[2] = v.z;
}

// What a batch is given, checked with the GIL held.
struct Batch {
  Side a, b;
  std::size_t n;
  int threads;

  Batch(const py::handle& shapes_a, const py::handle& shapes_b, const py::handle& poses_a, const py::handle& poses_b,
        int requested_threads)
      : a(read_side(shapes_a, poses_a, "a")), b(read_side(shapes_b, poses_b, "b")), n(pair_count(a, b)),
        threads(thread_count(requested_threads)) {}

  // Runs `one(k, workspace)` for every pair with the GIL released.
  template <class F>
  void for_each(F&& one) const {
    py::gil_scoped_release release;
    const int t = std::max(1, std::min<int>(threads, static_cast<int>(n / 16 + 1)));
    std::vector<OverlapWorkspace> work(static_cast<std::size_t>(t));
#pragma omp parallel for num_threads(t) schedule(dynamic, 16)
    for (std::int64_t k = 0; k < static_cast<std::int64_t>(n); ++k) {
#ifdef _OPENMP
      OverlapWorkspace& w = work[static_cast<std::size_t>(omp_get_thread_num())];
#else
      OverlapWorkspace& w = work[0];
#endif
      one(static_cast<std::size_t>(k), w);
    }
  }
};

// The arrays a batch returns, made before the GIL is released: each call
// adds one under its name and gives its memory.
struct Columns {
  py::ssize_t n;
  py::dict arrays;

  explicit Columns(std::size_t count) : n(static_cast<py::ssize_t>(count)) {}
  bool* flags(const char* name) { return add(py::array_t<bool>(n), name); }
  double* numbers(const char* name) { return add(py::array_t<double>(n), name); }
  double* rows(const char* name) { return add(py::array_t<double>({n, py::ssize_t{3}}), name); }

 private:
  template <class T>
  T* add(py::array_t<T> a, const char* name) {
    arrays[name] = a;
    return a.mutable_data();
  }
};

// An (N, 3, 3) array of triangles (pair, corner, axis), every number finite.
py::array_t<double, py::array::c_style | py::array::forcecast> triangles_of(const py::handle& value, const char* what) {
  const std::string name = std::string("triangle_distances: ") + what;
  auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
  if (!a) fail(name, "expected an array of shape (N, 3, 3): N triangles, 3 corners, x y z");
  if (a.ndim() != 3 || a.shape(1) != 3 || a.shape(2) != 3)
    fail(name, "expected an array of shape (N, 3, 3): N triangles, 3 corners, x y z");
  const double* v = a.data();
  for (py::ssize_t k = 0; k < a.size(); ++k)
    if (!std::isfinite(v[k])) fail(name, "triangle " + std::to_string(k / 9) + " has a coordinate that is not finite");
  return a;
}

}  // namespace

void bind_queries(py::module_& m) {
  py::class_<DistanceResult>(m, "Distance", "distance(): separation and closest points (world frame).")
      .def_readonly("intersect", &DistanceResult::intersect)
      .def_readonly("distance", &DistanceResult::distance)
      .def_property_readonly("witness_a", [](const DistanceResult& r) { return from_vec3(r.witness_a); })
      .def_property_readonly("witness_b", [](const DistanceResult& r) { return from_vec3(r.witness_b); })
      .def_property_readonly("normal", [](const DistanceResult& r) { return from_vec3(r.normal); },
                             "Unit, A -> B; zero when intersecting.")
      .def_property_readonly("status", [](const DistanceResult& r) { return gjk_status_name(r.status); })
      .def_readonly("iterations", &DistanceResult::iterations)
      .def("__repr__", [](const DistanceResult& r) {
        return "<gjkdem.Distance intersect=" + std::string(r.intersect ? "True" : "False") +
               " distance=" + std::to_string(r.distance) + ">";
      });
  py::class_<PenetrationResult>(m, "Penetration",
                                "penetration(): distance when apart, depth and normal (EPA) when intersecting.")
      .def_readonly("intersect", &PenetrationResult::intersect)
      .def_readonly("distance", &PenetrationResult::distance)
      .def_readonly("depth", &PenetrationResult::depth)
      .def_property_readonly("witness_a", [](const PenetrationResult& r) { return from_vec3(r.witness_a); })
      .def_property_readonly("witness_b", [](const PenetrationResult& r) { return from_vec3(r.witness_b); })
      .def_property_readonly("normal", [](const PenetrationResult& r) { return from_vec3(r.normal); },
                             "Unit, A -> B.")
      .def_readonly("iterations", &PenetrationResult::iterations)
      .def_property_readonly("gjk_status", [](const PenetrationResult& r) { return gjk_status_name(r.gjk_status); })
      .def_property_readonly("epa_status", [](const PenetrationResult& r) { return epa_status_name(r.epa_status); },
                             "How EPA ended (\"not_run\" when apart; \"out_of_memory\": best face so far)")
      .def_readonly("epa_iterations", &PenetrationResult::epa_iterations)
      .def("__repr__", [](const PenetrationResult& r) {
        return "<gjkdem.Penetration intersect=" + std::string(r.intersect ? "True" : "False") +
               " distance=" + std::to_string(r.distance) + " depth=" + std::to_string(r.depth) + ">";
      });
  py::class_<OverlapResult>(m, "Overlap", "overlap(): the region the two shapes share (the volume contact model).")
      .def_property_readonly("status", [](const OverlapResult& r) { return overlap_status_name(r.status); })
      .def_readonly("volume", &OverlapResult::volume)
      .def_property_readonly("centroid",
                             [](const OverlapResult& r) -> py::object {
                               if (r.status != OverlapStatus::Overlapping) return py::none();
                               return from_vec3(r.centroid);
                             })
      .def_property_readonly("contact_normal",
                             [](const OverlapResult& r) -> py::object {
                               if (!r.has_normal) return py::none();
                               return from_vec3(r.contact_normal);
                             })
      .def_readonly("contact_area", &OverlapResult::contact_area)
      .def_property_readonly("area_a", [](const OverlapResult& r) { return from_vec3(r.area_a); })
      .def_property_readonly("area_b", [](const OverlapResult& r) { return from_vec3(r.area_b); })
      .def("__repr__", [](const OverlapResult& r) {
        return "<gjkdem.Overlap " + std::string(overlap_status_name(r.status)) + " volume=" +
               std::to_string(r.volume) + ">";
      });

  const char* pose_doc = "Poses are None (the shape as given) or [x, y, z, qw, qx, qy, qz].";
  m.def(
      "intersect",
      [](const PyShape& a, const PyShape& b, const py::object& pa, const py::object& pb) {
        const Transform ta = placed(a, to_pose(pa, "pose_a")), tb = placed(b, to_pose(pb, "pose_b"));
        return intersect(convex_of(a, "a"), ta, convex_of(b, "b"), tb);
      },
      py::arg("a"), py::arg("b"), py::arg("pose_a") = py::none(), py::arg("pose_b") = py::none(), pose_doc);
  m.def(
      "distance",
      [](const PyShape& a, const PyShape& b, const py::object& pa, const py::object& pb) {
        return distance(convex_of(a, "a"), placed(a, to_pose(pa, "pose_a")), convex_of(b, "b"),
                        placed(b, to_pose(pb, "pose_b")));
      },
      py::arg("a"), py::arg("b"), py::arg("pose_a") = py::none(), py::arg("pose_b") = py::none(), pose_doc);
  m.def(
      "penetration",
      [](const PyShape& a, const PyShape& b, const py::object& pa, const py::object& pb) {
        return penetration(convex_of(a, "a"), placed(a, to_pose(pa, "pose_a")), convex_of(b, "b"),
                           placed(b, to_pose(pb, "pose_b")));
      },
      py::arg("a"), py::arg("b"), py::arg("pose_a") = py::none(), py::arg("pose_b") = py::none(), pose_doc);
  m.def(
      "overlap",
      [](const PyShape& a, const PyShape& b, const py::object& pa, const py::object& pb) {
        OverlapWorkspace work;
        return overlap(convex_of(a, "a"), placed(a, to_pose(pa, "pose_a")), convex_of(b, "b"),
                       placed(b, to_pose(pb, "pose_b")), work);
      },
      py::arg("a"), py::arg("b"), py::arg("pose_a") = py::none(), py::arg("pose_b") = py::none(), pose_doc);

  // Batches: a and b one shape or N, poses None or (N, 7), a dict of arrays back.
  const auto def_batch = [&m](const char* name, auto batch, const char* doc) {
    m.def(name, batch, py::arg("a"), py::arg("b"), py::arg("poses_a") = py::none(), py::arg("poses_b") = py::none(),
          py::arg("threads") = 0, doc);
  };
  py::class_<ShapeSet>(m, "ShapeSet",
                       "Convex shapes packed once into contiguous arrays, for batches over the same shapes again\n"
                       "and again (thousands of distinct shapes: the queries then read memory as the C++ does).")
      .def(py::init([](const py::sequence& items) {
             ShapeSet set;
             set.shapes.reserve(items.size()), set.offsets.reserve(items.size());
             for (const auto& item : items) {
               const PyShape* shape = shape_of(item);
               if (!shape) fail("ShapeSet", "expected a list of gjkdem.Shape");
               set.shapes.push_back(convex_of(*shape, "ShapeSet"));
               set.offsets.push_back(shape->offset);
             }
             if (set.shapes.empty()) fail("ShapeSet", "the list of shapes is empty");
             return set;
           }),
           py::arg("shapes"))
      .def("__len__", [](const ShapeSet& set) { return set.shapes.size(); });
  const char* batch_doc =
      "Batched query: a and b are a Shape, a list of N shapes or a ShapeSet of N; poses_a and poses_b None or\n"
      "(N, 7) arrays. Returns a dict of arrays, row k for pair k. threads = 0 uses every core.";
  def_batch(
      "intersect_batch",
      [](const py::object& a, const py::object& b, const py::object& pa, const py::object& pb, int threads) {
        const Batch in(a, b, pa, pb, threads);
        Columns out(in.n);
        bool* hit = out.flags("intersect");
        in.for_each([&](std::size_t k, OverlapWorkspace&) {
          hit[k] = intersect(in.a.shape(k), in.a.pose(k), in.b.shape(k), in.b.pose(k));
        });
        return out.arrays;
      },
      batch_doc);
  def_batch(
      "distance_batch",
      [](const py::object& a, const py::object& b, const py::object& pa, const py::object& pb, int threads) {
        const Batch in(a, b, pa, pb, threads);
        Columns out(in.n);
        bool* hit = out.flags("intersect");
        double* dist = out.numbers("distance");
        double *wa = out.rows("witness_a"), *wb = out.rows("witness_b"), *normal = out.rows("normal");
        in.for_each([&](std::size_t k, OverlapWorkspace&) {
          const DistanceResult r = distance(in.a.shape(k), in.a.pose(k), in.b.shape(k), in.b.pose(k));
          hit[k] = r.intersect, dist[k] = r.distance;
          put(wa, k, r.witness_a), put(wb, k, r.witness_b), put(normal, k, r.normal);
        });
        return out.arrays;
      },
      batch_doc);
  def_batch(
      "penetration_batch",
      [](const py::object& a, const py::object& b, const py::object& pa, const py::object& pb, int threads) {
        const Batch in(a, b, pa, pb, threads);
        Columns out(in.n);
        bool* hit = out.flags("intersect");
        double *dist = out.numbers("distance"), *depth = out.numbers("depth");
        double *wa = out.rows("witness_a"), *wb = out.rows("witness_b"), *normal = out.rows("normal");
        in.for_each([&](std::size_t k, OverlapWorkspace&) {
          const PenetrationResult r =
              penetration(in.a.shape(k), in.a.pose(k), in.b.shape(k), in.b.pose(k));
          hit[k] = r.intersect, dist[k] = r.distance, depth[k] = r.depth;
          put(wa, k, r.witness_a), put(wb, k, r.witness_b), put(normal, k, r.normal);
        });
        return out.arrays;
      },
      batch_doc);
  def_batch(
      "overlap_batch",
      [](const py::object& a, const py::object& b, const py::object& pa, const py::object& pb, int threads) {
        const Batch in(a, b, pa, pb, threads);
        Columns out(in.n);
        double *volume = out.numbers("volume"), *centroid = out.rows("centroid");
        double *normal = out.rows("contact_normal"), *area = out.numbers("contact_area");
        std::atomic<bool> unsupported = false;
        in.for_each([&](std::size_t k, OverlapWorkspace& w) {
          const OverlapResult r = overlap(in.a.shape(k), in.a.pose(k), in.b.shape(k), in.b.pose(k), w);
          if (r.status == OverlapStatus::Unsupported) unsupported = true;
          volume[k] = r.volume, area[k] = r.contact_area;
          put(centroid, k, r.status == OverlapStatus::Overlapping ? r.centroid : Vec3{NAN, NAN, NAN});
          put(normal, k, r.has_normal ? r.contact_normal : Vec3{NAN, NAN, NAN});
        });
        if (unsupported)
          throw py::value_error("overlap_batch: a pair has no exact overlap computation (polytopes, boxes, "
                                "triangles; tessellate curved shapes first)");
        return out.arrays;
      },
      "Batched overlap; centroid and contact_normal rows are NaN where there is none. See intersect_batch.");
  m.def(
      "triangle_distances",
      [](const py::handle& a, const py::handle& b) {
        const auto ta = triangles_of(a, "a"), tb = triangles_of(b, "b");
        if (ta.shape(0) != tb.shape(0))
          fail("triangle_distances", "a holds " + std::to_string(ta.shape(0)) + " triangles and b " +
                                         std::to_string(tb.shape(0)) + ": one pair per row");
        const std::size_t n = static_cast<std::size_t>(ta.shape(0));
        Columns out(n);
        double *dist = out.numbers("distance"), *wa = out.rows("witness_a"), *wb = out.rows("witness_b");
        const double *pa = ta.data(), *pb = tb.data();
        {
          py::gil_scoped_release release;
          const auto corner = [](const double* t, std::size_t k, int c) {
            return Vec3{t[9 * k + 3 * c], t[9 * k + 3 * c + 1], t[9 * k + 3 * c + 2]};
          };
          TrianglePairs pairs;
          pairs.blocks.reserve((n + kTriangleLanes - 1) / kTriangleLanes);
          for (std::size_t k = 0; k < n; ++k)
            pairs.push_back(corner(pa, k, 0), corner(pa, k, 1), corner(pa, k, 2), corner(pb, k, 0), corner(pb, k, 1),
                            corner(pb, k, 2));
          std::vector<TriangleDistanceBlock> r;
          triangle_distances(pairs, r);
          for (std::size_t k = 0; k < n; ++k) {
            const TriangleDistanceBlock& blk = r[k / kTriangleLanes];
            const std::size_t l = k % kTriangleLanes;
            dist[k] = blk.distance[l];
            for (int axis = 0; axis < 3; ++axis) {
              wa[3 * k + axis] = blk.witness_a[axis][l];
              wb[3 * k + axis] = blk.witness_b[axis][l];
            }
          }
        }
        return out.arrays;
      },
      py::arg("a"), py::arg("b"),
      "Distances of N triangle pairs with the batched closed-form kernel (exact, AVX2 or SSE2): a and b are\n"
      "(N, 3, 3) arrays (pair, corner, x y z). Returns a dict: distance (N,), 0 where a pair touches or\n"
      "intersects; witness_a, witness_b (N, 3), closest points (a point of both where they intersect).");
}

}  // namespace gjkdem::py_bind
