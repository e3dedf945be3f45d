#!/usr/bin/env python3
"""A small study in Python: pour random polyhedra into a box, let them settle,
and follow the bed's packing fraction and mean coordination number over time.

    PYTHONPATH=build/python python3 examples/python/bed_study.py [--grains 400] [--time 0.6] [--out study]

Writes study/bed.csv (one row per output) and study/bed.png (the two curves).
"""
import argparse
import csv
import pathlib

import numpy as np

import gjkdem


def random_grains(rng, count, size):
    """Distinct random polyhedra of about `size` across (hulls of 12 points on an ellipsoid)."""
    grains = []
    for _ in range(count):
        points = rng.normal(size=(12, 3))
        points /= np.linalg.norm(points, axis=1)[:, None]
        grains.append(gjkdem.Shape("polytope", vertices=points * size / 2 * rng.uniform(0.7, 1.0, size=3)))
    return grains


def build_bed(grains, side, seed):
    settings = gjkdem.Settings()  # the volume law, gravity along -z
    settings.threads = 0
    b = gjkdem.WorldBuilder(settings)
    b.add_material("rock", density=2600, youngs_modulus=2e6, restitution=0.3, friction=0.5, rolling_friction=0.05)
    b.add_box_walls([0, 0, 0], [side, side, 4 * side], "rock", open_top=True, thickness=side / 4)
    shapes = random_grains(np.random.default_rng(seed), 20, side / 8)
    b.fill_region(shapes, grains, [0, 0, 0], [side, side, 4 * side], "rock", seed=seed)
    return b.build()


def measure(world, grain_volume, side):
    """Packing fraction below the bed's surface, and mean contacts per grain."""
    moving = world.fixed == 0
    z = world.positions[moving, 2]
    # The surface: the mean height of the top 10% of grain centres; the layer
    # below 80% of it holds no surface roughness.
    top = np.sort(z)[-max(1, len(z) // 10):].mean()
    layer = 0.8 * top
    inside = z < layer
    fraction = grain_volume[moving][inside].sum() / (side * side * layer)
    c = world.contacts()
    ids = c["ids"]
    between_grains = (ids[:, 0] < 2**62) & np.isin(ids[:, 0], world.ids[moving])
    coordination = 2 * between_grains.sum() / moving.sum()
    return fraction, coordination


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--grains", type=int, default=400)
    p.add_argument("--time", type=float, default=0.6, help="simulated seconds")
    p.add_argument("--every", type=float, default=0.02, help="seconds between measurements")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--out", default="study")
    a = p.parse_args()

    side = 0.1
    world = build_bed(a.grains, side, a.seed)
    masses = world.masses()
    grain_volume = np.where(np.isfinite(masses), masses / 2600, 0.0)
    rows = []

    def observe(w, state):
        fraction, coordination = measure(w, grain_volume, side)
        rows.append((w.time, fraction, coordination, w.energies()["kinetic"]))
        print(f"t = {w.time:6.3f} s  packing {fraction:5.3f}  coordination {coordination:5.2f}", flush=True)

    world.run(a.time, output_every=a.every, observer=observe)

    out = pathlib.Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    with open(out / "bed.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["time", "packing_fraction", "coordination", "kinetic_energy"])
        w.writerows(rows)

    import matplotlib

    matplotlib.use("Agg")  # no display needed
    import matplotlib.pyplot as plt

    t, phi, z, _ = np.array(rows).T
    fig, left = plt.subplots(figsize=(7, 4))
    left.plot(t, phi, color="tab:blue")
    left.set_xlabel("time (s)")
    left.set_ylabel("packing fraction", color="tab:blue")
    right = left.twinx()
    right.plot(t, z, color="tab:red")
    right.set_ylabel("mean coordination number", color="tab:red")
    left.set_title(f"{a.grains} random polyhedra settling in a box")
    fig.tight_layout()
    fig.savefig(out / "bed.png", dpi=120)
    print(f"wrote {out / 'bed.csv'} and {out / 'bed.png'}")


if __name__ == "__main__":
    main()
