// The gjkdem Python module (imported as gjkdem, built as gjkdem._core).
#include "bindings.hpp"
#include "py_run.hpp"
#include "gjkdem/dem/world_builder.hpp"
#include "gjkdem/io/checkpoint.hpp"
#include "gjkdem/io/run_observers.hpp"
#include "gjkdem/io/scene.hpp"
#include "gjkdem/io/scene_run.hpp"

PYBIND11_MODULE(_core, m) {
  using namespace gjkdem;
  namespace py = pybind11;
  m.doc() = "gjkdem: exact convex collision queries and a DEM engine for non-spherical grains";
  m.attr("__version__") = io::version();
  // The library's errors, with its messages: bad input is a ValueError,
  // a run folder that cannot be used an OSError.
  py::register_exception<dem::BuildError>(m, "BuildError", PyExc_ValueError);
  py::register_exception<io::SceneError>(m, "SceneError", PyExc_ValueError);
  py::register_exception<io::CheckpointError>(m, "CheckpointError", PyExc_ValueError);
  py::register_exception<io::RunFolderError>(m, "RunFolderError", PyExc_OSError);
  py::register_exception<py_bind::RunError>(m, "RunError", PyExc_RuntimeError);
  py_bind::bind_shapes(m);
  py_bind::bind_queries(m);
  py_bind::bind_surfaces(m);
  py_bind::bind_world(m);
  py_bind::bind_scenes(m);
}
