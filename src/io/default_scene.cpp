// The scene `gjkdem run` runs when given no file (docs/scenes.md explains it).
#include "gjkdem/io/scene.hpp"

namespace gjkdem::io {

std::string_view default_scene_toml() {
  return R"toml(# gjkdem's built-in default scene: 2,000 random convex polyhedra (12
# vertices, 12 to 18 mm across) poured into a square hopper whose 100 mm
# outlet is open, discharged onto the floor 0.3 m below it. Soft particles
# (E = 0.3 MPa) keep the time step large enough for a run of a few minutes.

[simulation]
duration = 1.4
dt = "auto"
gravity = [0.0, 0.0, -9.81]
threads = 0
seed = 1

[output]
dir = "out"
every = 0.04
overwrite = false

[contact]
model = "volume"

[[material]]
name = "rock"
density = 2500.0
youngs_modulus = 3.0e5
poisson_ratio = 0.25
restitution = 0.5
friction = 0.5

[[material]]
name = "steel"
density = 7800.0
youngs_modulus = 3.0e5
poisson_ratio = 0.3
restitution = 0.5
friction = 0.3

[[wall]]
type = "plane"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
material = "steel"

# The hopper: four 20 mm plates inclined 34 degrees from the vertical, from
# the outlet (z = 0.3 m, 100 mm square) to the top (z = 0.6 m, 500 mm square).
[[body]]
shape = { type = "box", center = [0.0, 0.0, 0.0], half_extents = [0.01, 0.27, 0.180278] }
material = "steel"
position = [0.158321, 0.0, 0.444453]
rotation = [0.957092, 0.0, 0.289784, 0.0]
fixed = true

[[body]]
shape = { type = "box", center = [0.0, 0.0, 0.0], half_extents = [0.01, 0.27, 0.180278] }
material = "steel"
position = [-0.158321, 0.0, 0.444453]
rotation = [0.957092, 0.0, -0.289784, 0.0]
fixed = true

[[body]]
shape = { type = "box", center = [0.0, 0.0, 0.0], half_extents = [0.27, 0.01, 0.180278] }
material = "steel"
position = [0.0, 0.158321, 0.444453]
rotation = [0.957092, -0.289784, 0.0, 0.0]
fixed = true

[[body]]
shape = { type = "box", center = [0.0, 0.0, 0.0], half_extents = [0.27, 0.01, 0.180278] }
material = "steel"
position = [0.0, -0.158321, 0.444453]
rotation = [0.957092, 0.289784, 0.0, 0.0]
fixed = true

# One traced grain, dropped in the middle above the outlet.
[[body]]
name = "tracer"
shape = { type = "platonic", name = "cube", size = 0.015 }
material = "rock"
position = [0.0, 0.0, 0.75]

[[generator]]
count = 1999
shape = { type = "random_polyhedron", vertices = 12, size = [0.012, 0.018] }
material = "rock"
region = { min = [-0.23, -0.23, 0.62], max = [0.23, 0.23, 0.74] }
)toml";
}

}  // namespace gjkdem::io
