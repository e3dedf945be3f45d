#!/usr/bin/env python3
"""A heap's angle of repose from a lifted cylinder, at several frictions, from
one settled bed.

    PYTHONPATH=build/python python3 examples/python/repose_study.py [--grains 300] [--frictions 0.3 0.8] [--out repose]

1. settle: random polyhedra fill a cylinder standing on a floor and settle
   (a scene run into OUT/settle, as `gjkdem run` would);
2. for each friction, a new run from the settled bed (SceneRun(start_from=...),
   `gjkdem run --from` on the command line): the grains' friction changed,
   the cylinder lifted at a steady speed until it clears the bed, then the heap
   comes to rest (OUT/friction_F);
3. the heap's angle: the slope of its flank, fitted to the highest grain
   centres at each distance from the axis (heap_angle).

Writes OUT/repose.csv (friction, angle in degrees, heap radius and height).
The settled bed can also be kept as a scene to edit: gjkdem export OUT/settle.
"""
import argparse
import csv
import math
import pathlib
import sys

import numpy as np

import gjkdem

RADIUS = 0.035  # m, the cylinder's
HEIGHT = 0.6    # m


def scene_text(grains, friction, lift_speed, duration, settle_grains_in=True, seed=1):
    """The study's scene: a floor, a cylinder (lifted at lift_speed, m/s) and the grains."""
    generator = f"""
[[generator]]
count = {grains}
shape = {{ type = "random_polyhedron", vertices = 10, size = [0.010, 0.014] }}
material = "grain"
region = {{ type = "cylinder", base = [0.0, 0.0, 0.002], axis = [0.0, 0.0, 1.0], radius = {RADIUS * 0.95}, height = {HEIGHT * 0.9} }}
""" if settle_grains_in else ""
    return f"""
[simulation]
duration = {duration}
dt = "auto"
seed = {seed}
threads = 0

[output]
every = 0.05
checkpoint_every = 10

[contact]
model = "volume"

[[material]]
name = "grain"
density = 2600.0
youngs_modulus = 2.0e6
restitution = 0.3
friction = {friction}
rolling_friction = 0.05

[[material]]
name = "floor"
density = 7800.0
youngs_modulus = 2.0e6
restitution = 0.3
friction = 0.9

[[wall]]
type = "plane"
normal = [0.0, 0.0, 1.0]
material = "floor"

[[wall]]
type = "cylinder"
base = [0.0, 0.0, 0.0]
axis = [0.0, 0.0, 1.0]
radius = {RADIUS}
height = {HEIGHT}
bottom = false
material = "floor"
motion = {{ velocity = [0.0, 0.0, {lift_speed}] }}
{generator}"""


def heap_angle(positions, bins=12):
    """The heap's angle (degrees), its radius and height (m) from the grains' centres.

    The flank: the highest centre in each ring about the heap's axis (the
    centres' mean x, y), between a fifth and four fifths of the heap's radius
    (the 95th percentile of the distances), where the top's rounding and the
    toe's runners stay out; its least-squares slope is the angle's tangent.
    """
    p = np.asarray(positions, dtype=float)
    if len(p) < 10:
        raise ValueError("heap_angle needs at least 10 grains")
    axis = p[:, :2].mean(axis=0)
    r = np.linalg.norm(p[:, :2] - axis, axis=1)
    radius = float(np.percentile(r, 95))
    edges = np.linspace(0.2 * radius, 0.8 * radius, bins + 1)
    rings, tops = [], []
    for lo, hi in zip(edges[:-1], edges[1:]):
        inside = (r >= lo) & (r < hi)
        if inside.any():
            rings.append(0.5 * (lo + hi))
            tops.append(p[inside, 2].max())
    if len(rings) < 3:
        raise ValueError("heap_angle: too few grains on the heap's flank")
    slope = np.polyfit(rings, tops, 1)[0]
    return math.degrees(math.atan(max(0.0, -slope))), radius, float(p[:, 2].max())


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--grains", type=int, default=300)
    p.add_argument("--frictions", type=float, nargs="+", default=[0.3, 0.8])
    p.add_argument("--settle", type=float, default=0.8, help="simulated seconds for the bed to settle")
    p.add_argument("--lift-speed", type=float, default=0.1, help="m/s, the cylinder's")
    p.add_argument("--rest", type=float, default=0.5, help="simulated seconds after the cylinder cleared the bed")
    p.add_argument("--out", default="repose")
    p.add_argument("--quiet", action="store_true")
    a = p.parse_args(argv)
    out = pathlib.Path(a.out)
    out.mkdir(parents=True, exist_ok=True)

    # 1. One settled bed (the cylinder still).
    settle_scene = out / "settle.toml"
    settle_scene.write_text(scene_text(a.grains, a.frictions[0], 0.0, a.settle))
    settle = out / "settle"
    gjkdem.SceneRun(str(settle_scene), out=str(settle), overwrite=True).run(progress=not a.quiet)
    bed = gjkdem.load_run(str(settle)).world
    bed_top = float(bed.positions[bed.fixed == 0, 2].max())

    # 2. Each friction from that bed: the same bodies and shapes (the same
    # generator and seed), another material and a moving wall.
    lift = (bed_top + 0.01) / a.lift_speed  # s until the cylinder clears the bed
    rows = []
    for friction in a.frictions:
        name = f"friction_{friction:g}"
        scene = out / f"{name}.toml"
        scene.write_text(scene_text(a.grains, friction, a.lift_speed, lift + a.rest))
        run = gjkdem.SceneRun(str(scene), out=str(out / name), overwrite=True, start_from=str(settle))
        run.run(progress=not a.quiet)
        w = run.world
        angle, radius, height = heap_angle(w.positions[w.fixed == 0])
        rows.append((friction, angle, radius, height))
        print(f"friction {friction:g}: angle of repose {angle:.1f} degrees (heap radius {radius * 1e3:.0f} mm, "
              f"height {height * 1e3:.0f} mm)", flush=True)

    with open(out / "repose.csv", "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["friction", "angle_deg", "heap_radius_m", "heap_height_m"])
        writer.writerows(rows)
    print(f"wrote {out / 'repose.csv'}")
    return rows


if __name__ == "__main__":
    sys.exit(0 if main() else 1)
