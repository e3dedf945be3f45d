#!/usr/bin/env python3
"""The Python module against the C++ it calls (issue 13's goals, docs/benchmarks.md).

    PYTHONPATH=build/python python3 bench/python/bench_python.py build/gjkdem [--grains 1000]

1. Batched queries: the same pairs (distinct random polytopes, 4-64 vertices,
   written to a query file) timed by `gjkdem bench` in C++ and by
   penetration_batch / intersect_batch from Python on one thread; ratio of the
   per-pair times (goal: at most 1.2).
2. Stepping a settled bed of random polyhedra from a Python loop (step() once
   per iteration, reading the positions through the view) against
   World.run, whose loop is C++, over the same steps from the same
   checkpoint (goal: at most 5% more).
3. Copies: a view is made without copying (its base is the world), so a
   loop copies nothing per step that it does not ask for.
"""
import argparse
import json
import statistics
import subprocess
import tempfile
import time

import numpy as np

import gjkdem


def random_pairs(path, count, seed):
    rng = np.random.default_rng(seed)
    with open(path, "w") as f:
        for k in range(count):
            shapes = []
            for _ in range(2):
                n = int(rng.integers(4, 65))
                centre = rng.uniform(-0.6, 0.6, size=3)
                shapes.append({"type": "polytope", "vertices": (rng.normal(size=(n, 3)) * 0.5 + centre).tolist()})
            f.write(json.dumps({"id": str(k), "a": shapes[0], "b": shapes[1]}) + "\n")


def cpp_ns(cli, path, query, repeat):
    out = subprocess.run([cli, "bench", "--in", path, "--query", query, "--repeat", str(repeat)],
                         capture_output=True, text=True, check=True)
    return json.loads(out.stdout)["ns_per_query"]


def load_pairs(path):
    a, b = [], []
    for line in open(path):
        pair = json.loads(line)
        a.append(gjkdem.Shape.from_json(pair["a"]))
        b.append(gjkdem.Shape.from_json(pair["b"]))
    return a, b


def python_ns(a, b, query, repeat):
    call = {"penetration": gjkdem.penetration_batch, "intersect": gjkdem.intersect_batch,
            "distance": gjkdem.distance_batch}[query]
    call(a, b, threads=1)  # warm-up pass, as gjkdem bench makes one
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        call(a, b, threads=1)
        times.append(time.perf_counter() - t)
    return statistics.median(times) / len(a) * 1e9  # ShapeSet and list both have len()


def settled_bed(grains, seed, checkpoint):
    s = gjkdem.Settings()
    s.threads = 1
    b = gjkdem.WorldBuilder(s)
    b.add_material("rock", density=2600, youngs_modulus=2e6, restitution=0.3, friction=0.5, rolling_friction=0.05)
    side = 0.2
    b.add_box_walls([0, 0, 0], [side, side, 0.25], "rock", open_top=True, thickness=0.05)
    rng = np.random.default_rng(seed)
    shapes = [gjkdem.Shape("polytope", vertices=rng.normal(size=(12, 3)) * 0.002) for _ in range(20)]
    b.fill_region(shapes, grains, [0, 0, 0], [side, side, 0.25], "rock", seed=seed)
    w = b.build()
    dt = w.critical_time_step()
    t = time.perf_counter()
    w.run(0.4, dt=dt)
    print(f"  settled {grains} grains in {time.perf_counter() - t:.0f} s "
          f"({w.contact_count} contacts, kinetic {w.energies()['kinetic']:.2e} J)", flush=True)
    w.save_checkpoint(checkpoint, dt=dt)
    return w, dt


def main():
    p = argparse.ArgumentParser()
    p.add_argument("cli")
    p.add_argument("--pairs", type=int, nargs="+", default=[2000, 20000])
    p.add_argument("--grains", type=int, default=1000)
    p.add_argument("--steps", type=int, default=2000)
    p.add_argument("--repeat", type=int, default=5)
    a = p.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        print("1. batched queries on distinct random polytopes (4-64 vertices), one thread")
        for count in a.pairs:
            pairs = f"{tmp}/pairs{count}.jsonl"
            random_pairs(pairs, count, 1)
            a_shapes, b_shapes = load_pairs(pairs)  # once, as a user's shapes are made
            a_set, b_set = gjkdem.ShapeSet(a_shapes), gjkdem.ShapeSet(b_shapes)  # packed once, as the C++ reads them
            for q in ("intersect", "penetration"):
                cpp, py, packed = [], [], []
                for _ in range(a.repeat):  # alternated, so all see the same machine
                    cpp.append(cpp_ns(a.cli, pairs, q, 5))
                    py.append(python_ns(a_shapes, b_shapes, q, 5))
                    packed.append(python_ns(a_set, b_set, q, 5))
                cpp, py, packed = statistics.median(cpp), statistics.median(py), statistics.median(packed)
                print(f"  {count:6d} pairs {q:12s} C++ {cpp:8.1f} ns/pair   lists {py:8.1f} (ratio {py / cpp:.3f})   "
                      f"ShapeSets {packed:8.1f} (ratio {packed / cpp:.3f})", flush=True)

        if a.grains <= 0:
            return
        print(f"2. stepping a settled bed of {a.grains} random polyhedra, {a.steps} steps, one thread")
        ckpt = f"{tmp}/bed.ckpt"
        w, dt = settled_bed(a.grains, 1, ckpt)
        ratios = []
        for _ in range(a.repeat):
            w.load_checkpoint(ckpt)
            t = time.perf_counter()
            w.run(a.steps * dt, dt=dt)
            in_cpp = time.perf_counter() - t
            end_cpp = w.positions.copy()
            w.load_checkpoint(ckpt)
            t = time.perf_counter()
            top = 0.0
            for _ in range(a.steps):
                w.step(dt)
                top = max(top, w.positions[:, 2].max())
            in_python = time.perf_counter() - t
            same = np.array_equal(w.positions, end_cpp)
            ratios.append(in_python / in_cpp)
            print(f"  World.run {in_cpp / a.steps * 1e6:8.1f} us/step   Python loop {in_python / a.steps * 1e6:8.1f} "
                  f"us/step   ratio {in_python / in_cpp:.3f}   same end state: {same}")
        print(f"  median ratio {statistics.median(ratios):.3f}")

        view = w.positions
        print("3. copies: positions view owns its data:", view.flags.owndata, "| base is the world:",
              view.base is w)
        t = time.perf_counter()
        for _ in range(100000):
            w.positions
        print(f"  making a view: {(time.perf_counter() - t) / 100000 * 1e6:.2f} us")


if __name__ == "__main__":
    main()
