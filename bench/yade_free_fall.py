# The free fall of bench_dem_scaling (1,000 tumbling polyhedra, no contact) in
# Yade (Debian's yade package, its Polyhedra module), for the cost per
# particle-step side by side with gjkdem on the same grains
# (docs/benchmarks.md).
#
#   bench_dem_scaling --free-fall --export fall.txt      # prints the time step it uses
#   yade -j2 -n -x bench/yade_free_fall.py fall.txt DT [STEPS [FINAL]]
#
# FINAL: each grain's hull vertices at the end, world axes, from its centre
# of mass, one grain per line (as bench_dem_scaling --final writes them, for
# bench/compare_rotation.py).
#
# fall.txt: a first line to skip, then one grain per line as its world-frame
# hull vertices; fall.txt.spin: each grain's angular velocity (rad/s). No
# walls, no damping: gravity and rotation only, as in gjkdem's free fall.
import math
import sys
import time

from yade import O, polyhedra_utils
from yade.wrapper import (ForceResetter, InsertionSortCollider, Bo1_Polyhedra_Aabb, InteractionLoop,
                          Ig2_Polyhedra_Polyhedra_PolyhedraGeom, Ip2_PolyhedraMat_PolyhedraMat_PolyhedraPhys,
                          Law2_PolyhedraGeom_PolyhedraPhys_Volumetric, NewtonIntegrator, PolyhedraMat)
from yade.minieigenHP import Vector3

path, dt = sys.argv[1], float(sys.argv[2])
steps = int(sys.argv[3]) if len(sys.argv) > 3 else 4000
final = sys.argv[4] if len(sys.argv) > 4 else None

with open(path) as f:
    f.readline()
    hulls = []
    for line in f:
        c = [float(x) for x in line.split()]
        hulls.append([Vector3(c[i], c[i + 1], c[i + 2]) for i in range(0, len(c), 3)])
with open(path + ".spin") as f:
    spins = [Vector3(*(float(x) for x in line.split())) for line in f]

mat = PolyhedraMat(density=2500, young=2.7e9, poisson=0.25, frictionAngle=math.atan(0.5))
O.materials.append(mat)
ids = O.bodies.append([polyhedra_utils.polyhedra(mat, v=v) for v in hulls])
for i, w in zip(ids, spins):
    s = O.bodies[i].state
    s.angVel = w
    # An aspherical body turns by its angular momentum (NewtonIntegrator's
    # exactAsphericalRot): L = R I R^T w, I its principal moments.
    local = s.ori.conjugate() * w
    s.angMom = s.ori * Vector3(s.inertia[0] * local[0], s.inertia[1] * local[1], s.inertia[2] * local[2])

O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Polyhedra_Aabb()], verletDist=0.0005),  # 5% of a grain, as gjkdem's skin
    InteractionLoop([Ig2_Polyhedra_Polyhedra_PolyhedraGeom()], [Ip2_PolyhedraMat_PolyhedraMat_PolyhedraPhys()],
                    [Law2_PolyhedraGeom_PolyhedraPhys_Volumetric()]),
    NewtonIntegrator(damping=0, gravity=(0, 0, -9.81)),
]
O.dt = dt
O.run(1, True)  # start-up excluded, as in gjkdem
t0 = time.time()
O.run(steps, True)
seconds = time.time() - t0
n = len(hulls)
contacts = sum(1 for i in O.interactions if i.isReal)
print("yade free fall: N=%d steps=%d contacts=%d us/part-step=%.4f" % (n, steps, contacts, 1e6 * seconds / steps / n))
if final:
    with open(final, "w") as out:
        for i in ids:
            b = O.bodies[i]
            out.write(" ".join("%.17g %.17g %.17g" % tuple(b.state.ori * v) for v in b.shape.v) + "\n")
