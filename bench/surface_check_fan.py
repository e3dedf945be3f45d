#!/usr/bin/env python3
"""Time make_surface (through gjkdem.Surface) on a cylinder whose two caps
are fans of N triangles about their centres, as CAD closes a cylinder: the
surface check's cost in a vertex's valence (docs/benchmarks.md).

    PYTHONPATH=build/python python3 bench/surface_check_fan.py 1000 8000 32000
"""
import math
import sys
import time

import numpy as np

import gjkdem


def cylinder(n):
    angle = 2 * math.pi * np.arange(n) / n
    rim = np.stack([np.cos(angle), np.sin(angle)], 1)
    vertices = np.vstack([[[0, 0, 0.5], [0, 0, -0.5]], np.c_[rim, np.full(n, 0.5)], np.c_[rim, np.full(n, -0.5)]])
    top = lambda i: 2 + i % n
    bottom = lambda i: 2 + n + i % n
    triangles = []
    for i in range(n):
        triangles += [(0, top(i), top(i + 1)), (1, bottom(i + 1), bottom(i)),
                      (bottom(i), bottom(i + 1), top(i + 1)), (bottom(i), top(i + 1), top(i))]
    return vertices, np.array(triangles)


for n in map(int, sys.argv[1:] or ["1000", "8000", "32000"]):
    vertices, triangles = cylinder(n)
    start = time.perf_counter()
    surface = gjkdem.Surface(vertices, triangles)
    print(f"fans of {n} triangles ({4 * n} in all): {time.perf_counter() - start:.2f} s")
