# examples/scenes/rotating_drum_beads.toml in Yade (Debian's yade package), for
# a second code's dynamic angle of repose on the same inputs (docs/dem.md):
# the same drum mesh as facets turning at 2.198 rad/s, 6,000 beads of 5.95 mm,
# Hertz-Mindlin (Yade's MindlinPhys: E = 2.4 MPa, Poisson 0.37, restitution
# 0.9), sliding friction MU, no rolling resistance, no numerical damping.
#
#   yade -j2 -n -x bench/yade_drum.py examples/scenes/drum_beads.obj OUT.npz [MU] [DURATION] [DT] [THICKNESS] [SEED]
#   python3 examples/python/drum_angle.py OUT.npz --radius 0.069 --from 1.5
#
# OUT.npz holds the beads' centres every 0.05 s from t = 1 s (times, frames),
# which drum_angle.py measures as it measures a gjkdem run folder. Yade's
# facets have no thickness, so they are put where the beads touch gjkdem's
# drum: its triangles moved in by their margin under Hertz, half the scene's
# wall thickness (THICKNESS, 0.004 m): sides along their normals, caps along
# the axis.
import math
import sys
import time

import numpy as np
from yade import O, utils
from yade.wrapper import (ForceResetter, InsertionSortCollider, Bo1_Sphere_Aabb, Bo1_Facet_Aabb, InteractionLoop,
                          Ig2_Sphere_Sphere_ScGeom, Ig2_Facet_Sphere_ScGeom, Ip2_FrictMat_FrictMat_MindlinPhys,
                          Law2_ScGeom_MindlinPhys_Mindlin, RotationEngine, NewtonIntegrator, FrictMat, Sphere)
from yade.minieigenHP import Vector3

obj, out = sys.argv[1], sys.argv[2]
mu = float(sys.argv[3]) if len(sys.argv) > 3 else 0.3
duration = float(sys.argv[4]) if len(sys.argv) > 4 else 4.0
dt = float(sys.argv[5]) if len(sys.argv) > 5 else 3e-5  # under gjkdem's Hertz step (5.45e-5 s) and Yade's P-wave step
margin = (float(sys.argv[6]) if len(sys.argv) > 6 else 0.004) / 2
seed = int(sys.argv[7]) if len(sys.argv) > 7 else 1  # of the beads' starting places
radius, omega, count = 0.00595 / 2, 2.198, 6000

mat = FrictMat(density=1768, young=2.4e6, poisson=0.37, frictionAngle=math.atan(mu))
O.materials.append(mat)
vertices, triangles = [], []
for line in open(obj):
    p = line.split()
    if p and p[0] == "v":
        vertices.append(Vector3(*(float(x) for x in p[1:4])))
    elif p and p[0] == "f":
        triangles.append([int(q.split("/")[0]) - 1 for q in p[1:4]])
# The drum's surface: a regular prism of `sides` sides, its rims at +-half along y.
half = max(abs(v[1]) for v in vertices)
sides = sum(1 for v in vertices if v[1] == half and math.hypot(v[0], v[2]) > 1e-12)
inward = margin / math.cos(math.pi / sides)  # a vertex moves this far for its two sides to move by the margin
for v in vertices:
    r = math.hypot(v[0], v[2])
    if r > 1e-12:
        v[0], v[2] = v[0] * (r - inward) / r, v[2] * (r - inward) / r
    v[1] = math.copysign(half - margin, v[1])
print("yade drum: %d sides, surface apothem %.6f m, half length %.6f m" % (sides, max(math.hypot(v[0], v[2]) for v in vertices) * math.cos(math.pi / sides), half - margin))
drum = O.bodies.append([utils.facet([vertices[i] for i in t], material=mat, wire=True) for t in triangles])

# Beads on a jittered grid inside the drum (they fall and settle as the drum turns, as gjkdem's do).
rng = np.random.default_rng(seed)
half -= margin
spacing = 0.0062
sites = [(x, y, z) for y in np.arange(-half + spacing, half - spacing / 2, spacing)
         for x in np.arange(-0.063, 0.0631, spacing) for z in np.arange(-0.063, 0.0631, spacing)
         if x * x + z * z < 0.062 ** 2]
centres = np.array(sites)[rng.choice(len(sites), count, replace=False)] + rng.uniform(-2e-4, 2e-4, (count, 3))
O.bodies.append([utils.sphere(Vector3(*c), radius, material=mat) for c in centres])

O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()], verletDist=0.3 * radius),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()],
                    [Ip2_FrictMat_FrictMat_MindlinPhys(en=0.9, es=0.9)], [Law2_ScGeom_MindlinPhys_Mindlin()]),
    RotationEngine(ids=drum, rotationAxis=(0, 1, 0), rotateAroundZero=True, zeroPoint=(0, 0, 0), angularVelocity=omega),
    NewtonIntegrator(damping=0.0, gravity=(0, 0, -9.81)),
]
O.dt = dt
times, frames = [], []
every = int(round(0.05 / dt))
start = time.time()
while O.time < duration - 1e-9:
    O.run(every, True)
    if O.time > 1.0 - 1e-9:
        times.append(O.time)
        frames.append([[b.state.pos[0], b.state.pos[1], b.state.pos[2]] for b in O.bodies if isinstance(b.shape, Sphere)])
    print("yade drum: t = %.2f s, %.0f s" % (O.time, time.time() - start), flush=True)
np.savez(out, times=np.array(times), frames=np.array(frames))
