# The settled bed of bench_dem_scaling in Yade (Debian's yade package, its
# Polyhedra module with the volumetric law), for the per-particle-step cost
# side by side with gjkdem on the same machine (docs/benchmarks.md).
#
#   bench_dem_scaling --block block.txt --export bed 1000 10000 100000
#   yade -j2 -n -x bench/yade_bed.py bed1000.txt [STEPS]
#
# The bed file: "side_x side_y", then one body per line as its world-frame
# hull vertices (x y z ...). The box walls, material and time step follow
# bench_dem_scaling: density 2500, volume stiffness 2.7e9 N/m^3 (gjkdem's
# E* / R* for these grains), friction 0.5, gravity.
import math
import sys
import time

from yade import O, utils, polyhedra_utils
from yade.wrapper import (ForceResetter, InsertionSortCollider, Bo1_Polyhedra_Aabb, Bo1_Wall_Aabb, InteractionLoop,
                          Ig2_Polyhedra_Polyhedra_PolyhedraGeom, Ig2_Wall_Polyhedra_PolyhedraGeom,
                          Ip2_PolyhedraMat_PolyhedraMat_PolyhedraPhys, Law2_PolyhedraGeom_PolyhedraPhys_Volumetric,
                          NewtonIntegrator, PolyhedraMat)
from yade.minieigenHP import Vector3

path = sys.argv[1]
steps = int(sys.argv[2]) if len(sys.argv) > 2 else 20

with open(path) as f:
    side_x, side_y = (float(x) for x in f.readline().split())
    bodies = []
    for line in f:
        c = [float(x) for x in line.split()]
        bodies.append([Vector3(c[i], c[i + 1], c[i + 2]) for i in range(0, len(c), 3)])

mat = PolyhedraMat(density=2500, young=2.7e9, poisson=0.25, frictionAngle=math.atan(0.5))
O.materials.append(mat)
O.bodies.append([polyhedra_utils.polyhedra(mat, v=v) for v in bodies])
O.bodies.append(utils.wall(0, axis=2, sense=1, material=mat))
O.bodies.append(utils.wall(0, axis=0, sense=1, material=mat))
O.bodies.append(utils.wall(side_x, axis=0, sense=-1, material=mat))
O.bodies.append(utils.wall(0, axis=1, sense=1, material=mat))
O.bodies.append(utils.wall(side_y, axis=1, sense=-1, material=mat))

O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Polyhedra_Aabb(), Bo1_Wall_Aabb()], verletDist=0.0005),  # 5% of a grain
    InteractionLoop([Ig2_Polyhedra_Polyhedra_PolyhedraGeom(), Ig2_Wall_Polyhedra_PolyhedraGeom()],
                    [Ip2_PolyhedraMat_PolyhedraMat_PolyhedraPhys()],
                    [Law2_PolyhedraGeom_PolyhedraPhys_Volumetric()]),
    NewtonIntegrator(damping=0.3, gravity=(0, 0, -9.81)),
]
O.dt = 1.4e-5  # gjkdem's critical_time_step for this bed
O.run(5, True)  # contacts found, caches warm
t0 = time.time()
O.run(steps, True)
seconds = time.time() - t0
n = len(bodies)
contacts = sum(1 for i in O.interactions if i.isReal)
print("yade N=%d contacts=%d per_part=%.2f ms/step=%.3f us/part-step=%.3f" %
      (n, contacts, 2.0 * contacts / n, 1e3 * seconds / steps, 1e6 * seconds / steps / n))
