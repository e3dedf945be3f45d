#pragma once
// The parts of the gjkdem Python module, each binding one layer.
#include "convert.hpp"

namespace gjkdem::py_bind {

void bind_shapes(py::module_& m);   // shapes.cpp: gjkdem.Shape
void bind_queries(py::module_& m);  // queries.cpp: intersect, distance, penetration, overlap and their batches
void bind_surfaces(py::module_& m);  // surfaces.cpp: gjkdem.Surface, surface_overlap, surface_distance
void bind_world(py::module_& m);    // world.cpp: settings, builder, world, views, runs, checkpoints
void bind_scenes(py::module_& m);   // scenes.cpp: TOML scenes, run folders as `gjkdem run` writes them

}  // namespace gjkdem::py_bind
