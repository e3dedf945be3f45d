# The press of examples/scenes/press_crushing.toml in Yade (Debian's yade
# package, 2023.02a) with its polyhedra splitter (PolyhedraSplitter, J. Elias
# 2013), for a second code's fragment sizes on the same start
# (docs/breakage.md).
#
#   gjkdem run examples/scenes/press_crushing.toml --out RUN
#   PYTHONPATH=build/python yade -j2 -n -x bench/yade_crushing.py \
#       RUN OUT.npz [START] [YOUNG] [STRENGTH] [DT] [END] 2> yade.err
#   grep -c "Unhandled switch case" yade.err
#
# Defaults: START 0.24, YOUNG auto, STRENGTH weibull, DT 2e-5, END 0.5.
# Yade starts from gjkdem's frame at START (s; at 0.24 the bed has settled
# and the press is at 36 mm): the same grains (their hulls from
# view/shapes.bin placed by the frame's poses, with the frame's velocities),
# the same box and the press on gjkdem's path (down to 30 mm at 0.25 s, then
# at 92 mm/s to 7 mm at 0.5 s). The grains start with gjkdem's overlaps, so
# with its resting contact forces: they are not shrunk (gjkdem leaves resting
# grains overlapping by their weight's share, and the stiffness is matched
# per pair, below). Yade's hulls of the frame's vertices have the volumes of
# gjkdem's meshes to 3e-7. OUT.npz
# holds the grains' volumes at the end (volumes), and every 0.01 s and at the
# end (times) the number of grains (counts), the force on the press (press, N,
# pushing up) and the press's face height (press_z, m).
#
# What Yade does differently, and what the script does about it:
# - strength units: Yade's PolyhedraSplitter splits a grain when the von
#   Mises stress of its contacts (the same measure as gjkdem's) exceeds
#   strength / (r / 1000) with r the radius of the sphere of its volume in m,
#   i.e. strength * 1e6 / r_mm: a material strength of 1e5 means 3e10 Pa at
#   r = 3.3 mm, so no grain ever broke in the first runs of this script. The
#   script now hands Yade strength = sigma_c * r_mm * 1e-6 for the stress
#   sigma_c (Pa) it means.
# - strength: with STRENGTH = weibull (the default) each grain, and each
#   fragment at once after its split, gets its own material with a strength
#   drawn as gjkdem draws it (run.json's rock: mean strength of grains of
#   strength_size, weibull_modulus m, size effect (d / d0)^(-3/m)), from
#   numpy's generator (seed 1), so the same distribution but not gjkdem's
#   draws. A number gives Yade's deterministic law instead, STRENGTH / r_mm
#   Pa (STRENGTH in Pa mm; 1e5 is gjkdem's mean at every size when m = 3).
# - smallest size: grains smaller than run.json's unbreakable_below are made
#   unsplittable as soon as they appear, as in gjkdem (Yade has no such
#   limit of its own).
# - the cut: Yade cuts a grain by two planes through its centre at 45
#   degrees between the most and least compressed directions (up to four
#   pieces at once), gjkdem by one plane normal to the least compressed
#   direction (two pieces). Yade checks every 10 steps (2e-4 s), gjkdem every
#   step.
# - contact: Yade's volumetric law F = kn V, as gjkdem's normalized volume
#   law F = k V; Yade takes kn = Ea Eb / (Ea + Eb) from the two bodies'
#   "young" (measured: 6e8 and 2e8 give 1.5e8 N/m^3), gjkdem k = E* / R*
#   with R* the pair's effective radius (sphere of equal volume; a wall
#   infinite). With YOUNG = auto each grain gets Yade young 4 E* / r (r its
#   own radius, refreshed for fragments), so two grains of radius r get
#   gjkdem's 2 E* / r exactly (unequal radii: Yade's 11% softer for a
#   ratio of 2),
#   and the steel young 4 E* / (3 r50) (r50 the median grain radius at
#   START), so a grain of r50 on a wall gets gjkdem's E* / r; fragments
#   feel a wall softer than in gjkdem (1.9x at 3 mm, 3.5x at 1.5 mm). A
#   number gives that Yade young to all grains and a third of it to steel
#   (the first runs gave 3e8 to both: kn 1.5e8 for every pair).
# - tangential: Yade's shear spring ks = kn * poisson (0.25 kn) against
#   gjkdem's 2/7 k; Coulomb friction as gjkdem's pairs have it (the
#   geometric mean: 0.5 between grains, sqrt(0.5 * 0.3) = 0.39 on steel),
#   given to Yade, which takes the smaller angle of the two materials, as
#   steel's; gjkdem adds rocking and twisting resistance of the contact
#   area, Yade neither (gjkdem's own run without rocking resistance pushes
#   the press with 0.31, 3.2, 10.5 and 25.9 N at 0.44, 0.46, 0.48 and
#   0.5 s, against 0.84, 4.0, 12.1 and 28.6 N with it).
# - damping: Yade's volumetric law has no dashpot: Newton's local damping
#   0.3 instead of gjkdem's restitution 0.3.
# - box and press: Yade's are fixed polyhedra slabs (floor and walls 10 mm
#   thick, gjkdem's box 15 mm), the press a 29.8 mm square slab moved by its
#   velocity each step; gjkdem's press is an infinite plane.
# - "Unhandled switch case:0, function do_intersect" (Polyhedra_support.cpp):
#   Yade 2023.02a warns whenever it tests a pair of polyhedra with no cached
#   separating plane (a pair whose boxes overlap but which did not touch the
#   step before, or a new pair; a later Yade source has a case 0), then
#   does the full test: noise, once per such pair and step (1,008,046 and
#   1,070,025 in two runs from 0.24 s to 0.5 s, 13,000 steps). Contacts are not lost: Yade's
#   bed has 76 touching pairs at 0.25 s as gjkdem's at 0.24 s, and 81 at
#   0.41 s in a run from 0.40 s
#   (gjkdem 78 at 0.40 s); the pairs' kn at the start are within 10% of
#   gjkdem's E* / R* (49 of 76 within 0.5%).
# - fragments: Yade's four-way cut can leave pieces below 3/4 of
#   unbreakable_below (1.5 mm seen), which gjkdem's halving cannot.
import json
import math
import os
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
young_arg = sys.argv[4] if len(sys.argv) > 4 else "auto"
strength_arg = sys.argv[5] if len(sys.argv) > 5 else "weibull"
dt = float(sys.argv[6]) if len(sys.argv) > 6 else 2e-5
end = float(sys.argv[7]) if len(sys.argv) > 7 else 0.5
CHECK = 10  # steps between the splitter's checks

with open(os.path.join(run, "run.json")) as f:
    materials = {m["name"]: m for m in json.load(f)["scene"]["material"]}
rock_in, steel_in = materials["rock"], materials["steel"]
e_star = 1 / ((1 - rock_in["poisson_ratio"] ** 2) / rock_in["youngs_modulus"] +
              (1 - rock_in["poisson_ratio"] ** 2) / rock_in["youngs_modulus"])  # grain on grain
weibull_m = rock_in["weibull_modulus"]
rng = np.random.default_rng(1)

view = gjkdem.read_view(run)
times = view.index["time"]  # a structured array of index.csv
k = int(np.argmin(np.abs(times - start)))
frame = view.frame(k)
t0 = float(frame.time)


def rotate(q, v):  # q = (w, x, y, z) applied to rows of v
    w, x, y, z = q
    r = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                  [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                  [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])
    return v @ r.T


def mesh_volume(vertices, triangles):
    a, b, c = (vertices[triangles[:, i]] for i in range(3))
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6)


hulls, gjkdem_volumes = [], []
for i in range(len(frame.positions)):
    if frame.flags[i]:
        continue  # the box's slabs: made below
    vertices, triangles = view.templates[frame.templates[i]]
    vertices = vertices.astype(float)
    gjkdem_volumes.append(mesh_volume(vertices, triangles.reshape(-1, 3).astype(int)))
    hulls.append((rotate(frame.orientations[i].astype(float), vertices) + frame.positions[i].astype(float), i))
r50 = float(np.median((3 * np.array(gjkdem_volumes) / (4 * math.pi)) ** (1 / 3)))

if young_arg == "auto":
    grain_young = lambda r: 4 * e_star / r
    steel_young = 4 * e_star / (3 * r50)
else:
    grain_young = lambda r: float(young_arg)
    steel_young = float(young_arg) / 3


def strength_of(d):  # the stress (Pa) at which a grain of size d (m) breaks
    if strength_arg == "weibull":
        u = rng.random()
        return (rock_in["strength"] / math.gamma(1 + 1 / weibull_m) * (d / rock_in["strength_size"]) ** (-3 / weibull_m)
                * (-math.log(1 - u)) ** (1 / weibull_m))
    return float(strength_arg) / (1e3 * d / 2)  # STRENGTH / r_mm


def rock_material(volume):  # a grain's own material, for its size
    d = (6 * volume / math.pi) ** (1 / 3)
    sigma = strength_of(d)
    m = PolyhedraMat(density=rock_in["density"], young=grain_young(d / 2), poisson=rock_in["poisson_ratio"],
                     frictionAngle=math.atan(rock_in["friction"]), IsSplitable=d >= rock_in["unbreakable_below"],
                     strength=sigma * (1e3 * d / 2) * 1e-6)  # Yade's units: see the header
    O.materials.append(m)
    return m


# gjkdem's pair friction is the geometric mean of the two materials', Yade's the smaller angle: steel gets
# gjkdem's rock-on-steel value, the smaller of the two.
steel = PolyhedraMat(density=steel_in["density"], young=steel_young, poisson=steel_in["poisson_ratio"],
                     frictionAngle=math.atan(math.sqrt(rock_in["friction"] * steel_in["friction"])), IsSplitable=False)
O.materials.append(steel)

grains, known = [], {}  # known: a grain's id -> the volume its material was drawn for
worst = 0.0
for (world, i), v_gjkdem in zip(hulls, gjkdem_volumes):
    b = polyhedra_utils.polyhedra(steel, v=[Vector3(*p) for p in world])
    volume = b.shape.GetVolume()
    worst = max(worst, abs(volume / v_gjkdem - 1))
    b.mat = rock_material(volume)
    b.state.mass = b.mat.density * volume
    b.state.inertia = b.shape.GetInertia() * b.mat.density
    b.state.vel = Vector3(*frame.velocities[i].astype(float))
    b.state.angVel = Vector3(*frame.angular_velocities[i].astype(float))
    grains.append(O.bodies.append(b))
    known[grains[-1]] = volume
print(f"yade: {len(grains)} grains, volumes within {worst:.1e} of gjkdem's meshes; r50 {1e3 * r50:.2f} mm, "
      f"E* {e_star:.4g} Pa, steel young {steel_young:.4g}")


def slab(lo, hi):
    corners = [(x, y, z) for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]
    return O.bodies.append(polyhedra_utils.polyhedra(steel, v=[Vector3(*c) for c in corners], fixed=True))


# The box of the scene: 30 x 30 mm inside, 100 mm high, slabs 10 mm thick.
h, t = 0.015, 0.01
steel_ids = {slab((-h - t, -h - t, -t), (h + t, h + t, 0)), slab((-h - t, -h - t, 0), (-h, h + t, 0.1)),
             slab((h, -h - t, 0), (h + t, h + t, 0.1)), slab((-h, -h - t, 0), (h, -h, 0.1)),
             slab((-h, h, 0), (h, h + t, 0.1))}


def press_height(time):  # the plate's face, on gjkdem's motion table
    if time <= 0.15:
        return 0.095
    if time <= 0.25:
        return 0.095 - 0.065 * (time - 0.15) / 0.1
    return 0.03 - 0.023 * (min(time, end) - 0.25) / 0.25


press = slab((-h + 1e-4, -h + 1e-4, press_height(t0)), (h - 1e-4, h - 1e-4, press_height(t0) + 0.01))
steel_ids.add(press)


def grain_bodies():
    return [b for b in O.bodies if b and b.id not in steel_ids]


def refresh():  # after the splitter: fragments get their own draw and stiffness, small ones stop breaking
    for b in grain_bodies():
        volume = b.shape.GetVolume()
        if b.id not in known or abs(volume / known[b.id] - 1) > 1e-9:
            b.mat = rock_material(volume)
            known[b.id] = volume


counts, stamps, press_force, press_z = [], [], [], []


def drive():  # Yade's clock starts at 0: gjkdem's time is t0 + O.time
    now = t0 + O.time
    O.bodies[press].state.vel = Vector3(0, 0, (press_height(now + dt) - press_height(now)) / dt)


def record():
    stamps.append(t0 + O.time)
    counts.append(len(grain_bodies()))
    press_force.append(float(O.forces.f(press)[2]))
    press_z.append(float(O.bodies[press].state.pos[2]) - 0.005)
    print(f"yade: t = {stamps[-1]:.3f} s, press at {1e3 * press_z[-1]:.2f} mm pushed with {press_force[-1]:.3f} N, "
          f"{counts[-1]} grains, {sum(1 for i in O.interactions if i.isReal)} contacts", flush=True)


O.dt = dt
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Polyhedra_Aabb()], verletDist=0.0005),
    InteractionLoop([Ig2_Polyhedra_Polyhedra_PolyhedraGeom()], [Ip2_PolyhedraMat_PolyhedraMat_PolyhedraPhys()],
                    [Law2_PolyhedraGeom_PolyhedraPhys_Volumetric()]),
    NewtonIntegrator(damping=0.3, gravity=(0, 0, -9.81)),  # the volumetric law has no dashpot
    PyRunner(command="drive()", iterPeriod=1),
    PolyhedraSplitter(iterPeriod=CHECK),
    PyRunner(command="refresh()", iterPeriod=CHECK),  # same steps, after the splitter
    PyRunner(command="record()", virtPeriod=0.01),
]
steps = int(round((end - t0) / dt))
O.run(steps, True)
record()
volumes = np.array([b.shape.GetVolume() for b in grain_bodies()])
np.savez(out, volumes=volumes, times=np.array(stamps), counts=np.array(counts), press=np.array(press_force),
         press_z=np.array(press_z), start=t0)
sizes = np.sort((6 * volumes / math.pi) ** (1 / 3))
print(f"yade: {len(sizes)} grains from {len(grains)} at t = {t0:.3f} s; sizes (mm) min {1e3 * sizes[0]:.2f}, "
      f"median {1e3 * np.median(sizes):.2f}, max {1e3 * sizes[-1]:.2f}")
