// gjkdem.Surface (a closed triangle surface, convex or not), its overlap
// and distance with another (docs/contact.md, "Surfaces").
#include <cmath>
#include <memory>
#include <string>

#include "bindings.hpp"
#include "gjkdem/collide/surface_distance.hpp"
#include "gjkdem/contact/surface_overlap.hpp"

namespace gjkdem::py_bind {
namespace {

std::shared_ptr<const Surface> surface_from_arrays(const py::handle& vertices, const py::handle& triangles) {
  TriangleArrays t = triangles_from_arrays(vertices, triangles);
  try {
    py::gil_scoped_release unlocked;  // the self-intersection check can take a while on big surfaces
    return std::make_shared<const Surface>(make_surface(std::move(t.points), std::move(t.corners)));
  } catch (const SurfaceError& e) {
    throw py::value_error(std::string("not a closed surface: ") + e.what());
  }
}

py::dict patch_dict(const SurfacePatch& p) {
  py::dict d;
  const Vec3 m = p.area_a - p.area_b;
  d["volume"] = p.volume;
  d["centroid"] = from_vec3(p.centroid);
  d["normal"] = length(m) > 0 ? py::object(from_vec3(m / length(m))) : py::object(py::none());
  d["area"] = 0.5 * length(m);
  return d;
}

}  // namespace

void bind_surfaces(py::module_& m) {
  py::class_<Surface, std::shared_ptr<Surface>>(m, "Surface",
                                                "A closed triangle surface, convex or not: the solid it bounds "
                                                "(vertices (N, 3), triangles (M, 3) counter-clockwise from outside).")
      .def(py::init([](const py::handle& vertices, const py::handle& triangles) {
             return std::const_pointer_cast<Surface>(surface_from_arrays(vertices, triangles));
           }),
           py::arg("vertices"), py::arg("triangles"))
      .def_property_readonly("volume", [](const Surface& s) { return s.volume; })
      .def_property_readonly("centroid", [](const Surface& s) { return from_vec3(s.centroid); })
      .def_property_readonly("triangle_count", [](const Surface& s) { return s.triangles.size(); })
      .def_property_readonly("vertex_count", [](const Surface& s) { return s.vertices.size(); })
      .def("__repr__", [](const Surface& s) {
        return "<gjkdem.Surface " + std::to_string(s.vertices.size()) + " vertices, " +
               std::to_string(s.triangles.size()) + " triangles>";
      });

  py::class_<Shell, std::shared_ptr<Shell>>(m, "Shell",
                                            "A thin shell: triangles, open or closed (vertices (N, 3), triangles "
                                            "(M, 3)), with a thickness (m): a body of its own under the Hertz and "
                                            "linear laws (docs/scenes.md, type = \"shell\").")
      .def(py::init([](const py::handle& vertices, const py::handle& triangles, double thickness) {
             TriangleArrays t = triangles_from_arrays(vertices, triangles);
             try {
               return std::make_shared<Shell>(make_shell(std::move(t.points), std::move(t.corners), thickness));
             } catch (const ShellError& e) {
               throw py::value_error(std::string("not a shell: ") + e.what());
             }
           }),
           py::arg("vertices"), py::arg("triangles"), py::arg("thickness"))
      .def_property_readonly("volume", [](const Shell& s) { return s.mass.volume; })
      .def_property_readonly("centroid", [](const Shell& s) { return from_vec3(s.mass.centroid); })
      .def_property_readonly("thickness", [](const Shell& s) { return 2 * s.margin; })
      .def_property_readonly("area", [](const Shell& s) { return s.area; })
      .def_property_readonly("triangle_count", [](const Shell& s) { return s.triangles.size(); })
      .def_property_readonly("vertex_count", [](const Shell& s) { return s.vertices.size(); })
      .def("__repr__", [](const Shell& s) {
        return "<gjkdem.Shell " + std::to_string(s.vertices.size()) + " vertices, " +
               std::to_string(s.triangles.size()) + " triangles, " + std::to_string(2 * s.margin) + " m thick>";
      });

  py::class_<SurfaceOverlap>(m, "SurfaceOverlap", "surface_overlap(): A ∩ B of two surfaces and its pieces.")
      .def_readonly("intersect", &SurfaceOverlap::intersect)
      .def_readonly("volume", &SurfaceOverlap::volume)
      .def_property_readonly("centroid", [](const SurfaceOverlap& o) {
        return o.volume > 0 ? py::object(from_vec3(o.centroid)) : py::object(py::none());
      })
      .def_property_readonly("area_a", [](const SurfaceOverlap& o) { return from_vec3(o.area_a); })
      .def_property_readonly("area_b", [](const SurfaceOverlap& o) { return from_vec3(o.area_b); })
      .def_property_readonly("contact_normal", [](const SurfaceOverlap& o) {
        const Vec3 n = o.area_a - o.area_b;
        return o.volume > 0 && length(n) > 0 ? py::object(from_vec3(n / length(n))) : py::object(py::none());
      })
      .def_property_readonly("patches", [](const SurfaceOverlap& o) {
        py::list list;
        for (const SurfacePatch& p : o.patches) list.append(patch_dict(p));
        return list;
      })
      .def("__repr__", [](const SurfaceOverlap& o) {
        return "<gjkdem.SurfaceOverlap volume=" + std::to_string(o.volume) + " patches=" +
               std::to_string(o.patches.size()) + ">";
      });

  m.def(
      "surface_overlap",
      [](const Surface& a, const Surface& b) {
        py::gil_scoped_release unlocked;
        return surface_overlap(a, b);
      },
      py::arg("a"), py::arg("b"), "The overlap of two surfaces given in one frame (docs/contact.md, \"Surfaces\").");
  m.def(
      "surface_distance",
      [](const Surface& a, const Surface& b) {
        SurfaceDistance d;
        {
          py::gil_scoped_release unlocked;
          d = surface_distance(a, b);
        }
        py::dict out;
        out["distance"] = d.distance;
        out["witness_a"] = from_vec3(d.witness_a);
        out["witness_b"] = from_vec3(d.witness_b);
        return out;
      },
      py::arg("a"), py::arg("b"),
      "The least distance between the two surfaces' triangles and a closest pair of points (of separated solids: "
      "their distance).");
}

}  // namespace gjkdem::py_bind
