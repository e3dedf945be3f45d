# The press of examples/scenes/press_crushing.toml in Yade (Debian's yade
# package) with its polyhedra splitter (PolyhedraSplitter, J. Elias 2013),
# for a second code's fragment sizes on the same start (docs/breakage.md).
#
#   gjkdem run examples/scenes/press_crushing.toml --out RUN
#   PYTHONPATH=build/python yade -j2 -n -x bench/yade_crushing.py RUN OUT.npz [START] [YOUNG] [STRENGTH] [DT] [END]
#
# Yade starts from gjkdem's frame at START (s, default 0.24: the bed has
# settled and the press is 6 mm above it): the same grains (their hulls from
# view/shapes.bin placed by the frame's poses), the same box and the press
# on gjkdem's path (down to 30 mm at 0.25 s, then at 92 mm/s to 7 mm at
# 0.5 s). OUT.npz holds the grains' volumes at the end (volumes) and the
# number of grains (grains) every 0.01 s (times, counts).
#
# The codes' laws differ where Yade has no counterpart, as stated here:
# - contact: Yade's volumetric law F = kn V with kn = young / 2 for two
#   equal materials; YOUNG (default 3e8) makes kn match gjkdem's k = E* / r
#   for grains of r = 3.5 mm (E = 1 MPa, Poisson 0.25);
# - strength: Yade splits a grain when the von Mises stress of its contacts
#   exceeds STRENGTH / r (r the radius of the sphere of its volume, in mm):
#   a deterministic size effect ~ 1/d, against gjkdem's Weibull draws with
#   d^(-3/m) (m = 3 in the example: also ~ 1/d). STRENGTH (default 1e5 Pa mm)
#   gives 2e4 Pa at d = 10 mm, gjkdem's mean there;
# - the cut: Yade cuts a grain by two planes at 45 degrees between the most
#   and least compressed directions (four pieces at most), gjkdem by one
#   plane normal to the least compressed (two pieces), and Yade has no
#   smallest size that stops the cascade (gjkdem: unbreakable_below).
import math
import sys

import numpy as np
import gjkdem
from yade import O, polyhedra_utils
from yade.wrapper import (ForceResetter, InsertionSortCollider, Bo1_Polyhedra_Aabb, InteractionLoop,
                          Ig2_Polyhedra_Polyhedra_PolyhedraGeom, Ip2_PolyhedraMat_PolyhedraMat_PolyhedraPhys,
                          Law2_PolyhedraGeom_PolyhedraPhys_Volumetric, NewtonIntegrator, PolyhedraSplitter,
                          PyRunner, PolyhedraMat)
from yade.minieigenHP import Vector3

run, out = sys.argv[1], sys.argv[2]
start = float(sys.argv[3]) if len(sys.argv) > 3 else 0.24
young = float(sys.argv[4]) if len(sys.argv) > 4 else 3e8
strength = float(sys.argv[5]) if len(sys.argv) > 5 else 1e5
dt = float(sys.argv[6]) if len(sys.argv) > 6 else 5e-6
end = float(sys.argv[7]) if len(sys.argv) > 7 else 0.5

view = gjkdem.read_view(run)
times = view.index["time"]  # a structured array of index.csv
k = int(np.argmin(np.abs(times - start)))
frame = view.frame(k)
t0 = float(frame.time)

rock = PolyhedraMat(density=2500, young=young, poisson=0.25, frictionAngle=math.atan(0.5), IsSplitable=True,
                    strength=strength)
steel = PolyhedraMat(density=7800, young=young, poisson=0.25, frictionAngle=math.atan(0.3), IsSplitable=False)
O.materials.append(rock)
O.materials.append(steel)


def rotate(q, v):  # q = (w, x, y, z) applied to rows of v
    w, x, y, z = q
    r = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                  [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                  [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])
    return v @ r.T


grains = []
for i in range(len(frame.positions)):
    if frame.flags[i]:
        continue  # the box's slabs: made below
    vertices, _ = view.templates[frame.templates[i]]
    world = rotate(frame.orientations[i].astype(float), vertices.astype(float)) + frame.positions[i].astype(float)
    b = polyhedra_utils.polyhedra(rock, v=[Vector3(*p) for p in world])
    b.state.vel = Vector3(*frame.velocities[i].astype(float))
    b.state.angVel = Vector3(*frame.angular_velocities[i].astype(float))
    grains.append(O.bodies.append(b))


def slab(lo, hi, material):
    corners = [(x, y, z) for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]
    return O.bodies.append(polyhedra_utils.polyhedra(material, v=[Vector3(*c) for c in corners], fixed=True))


# The box of the scene: 30 x 30 mm inside, 100 mm high, slabs 10 mm thick.
h, t = 0.015, 0.01
slab((-h - t, -h - t, -t), (h + t, h + t, 0), steel)
slab((-h - t, -h - t, 0), (-h, h + t, 0.1), steel)
slab((h, -h - t, 0), (h + t, h + t, 0.1), steel)
slab((-h, -h - t, 0), (h, -h, 0.1), steel)
slab((-h, h, 0), (h, h + t, 0.1), steel)


def press_height(time):  # the plate's face, on gjkdem's motion table
    if time <= 0.15:
        return 0.095
    if time <= 0.25:
        return 0.095 - 0.065 * (time - 0.15) / 0.1
    return 0.03 - 0.023 * (min(time, end) - 0.25) / 0.25


press = slab((-h + 1e-4, -h + 1e-4, press_height(t0)), (h - 1e-4, h - 1e-4, press_height(t0) + 0.01), steel)
O.bodies[press].state.blockedDOFs = "xyzXYZ"

counts, stamps = [], []


def drive():  # Yade's clock starts at 0: gjkdem's time is t0 + O.time
    now = t0 + O.time
    O.bodies[press].state.vel = Vector3(0, 0, (press_height(now + dt) - press_height(now)) / dt)


def record():
    stamps.append(t0 + O.time)
    counts.append(sum(1 for b in O.bodies if b and not b.state.blockedDOFs and b.material.id == rock.id))


O.dt = dt
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Polyhedra_Aabb()], verletDist=0.0005),
    InteractionLoop([Ig2_Polyhedra_Polyhedra_PolyhedraGeom()], [Ip2_PolyhedraMat_PolyhedraMat_PolyhedraPhys()],
                    [Law2_PolyhedraGeom_PolyhedraPhys_Volumetric()]),
    NewtonIntegrator(damping=0.3, gravity=(0, 0, -9.81)),  # the volumetric law has no dashpot
    PyRunner(command="drive()", iterPeriod=1),
    PolyhedraSplitter(iterPeriod=100),
    PyRunner(command="record()", virtPeriod=0.01),
]
steps = int(round((end - t0) / dt))
O.run(steps, True)
volumes = np.array([b.shape.GetVolume() for b in O.bodies if b and b.material.id == rock.id and not b.state.blockedDOFs])
np.savez(out, volumes=volumes, times=np.array(stamps), counts=np.array(counts), start=t0)
sizes = np.sort((6 * volumes / math.pi) ** (1 / 3))
print(f"yade: {len(sizes)} grains from {len(grains)} at t = {t0:.3f} s; sizes (mm) min {1e3 * sizes[0]:.2f}, "
      f"median {1e3 * np.median(sizes):.2f}, max {1e3 * sizes[-1]:.2f}")
