#!/usr/bin/env python3
"""Writes the closed surfaces of the surface-grain example scenes (OBJ):
rock.obj, a star-shaped, non-convex rock of 320 triangles (an icosphere
twice subdivided, its radius varied by a few bumps and dents), and
ring.obj, a torus (major radius 10 mm, tube 2 mm). Deterministic:
python3 make_surface_meshes.py rewrites the same files."""
import math
import random
import sys
from pathlib import Path


def icosphere(subdivisions):
    t = (1 + 5 ** 0.5) / 2
    vertices = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
                (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    vertices = [tuple(c / math.sqrt(sum(x * x for x in v)) for c in v) for v in vertices]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
             (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11),
             (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(subdivisions):
        middle = {}

        def mid(i, j):
            key = (min(i, j), max(i, j))
            if key not in middle:
                p = [(a + b) / 2 for a, b in zip(vertices[i], vertices[j])]
                n = math.sqrt(sum(x * x for x in p))
                vertices.append(tuple(x / n for x in p))
                middle[key] = len(vertices) - 1
            return middle[key]

        faces = [f for a, b, c in faces
                 for f in ((a, mid(a, b), mid(a, c)), (b, mid(b, c), mid(a, b)), (c, mid(a, c), mid(b, c)),
                           (mid(a, b), mid(b, c), mid(a, c)))]
    return vertices, faces


def rock(size):
    rng = random.Random(7)
    directions, faces = icosphere(2)
    # Six dents in the middle of its sides (the hull bridges them) and three
    # knobs between them, jittered.
    dents = [(0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1), (1, 1, 0.3), (-1, -1, -0.3)]
    knobs = [(1, -1, 1), (-1, 1, 1), (1, 0.2, -1)]
    bumps = [(tuple(c + rng.gauss(0, 0.1) for c in d), -0.5) for d in dents] + \
            [(tuple(c + rng.gauss(0, 0.1) for c in d), 0.2) for d in knobs]
    bumps = [(tuple(c / math.sqrt(sum(x * x for x in d)) for c in d), h) for d, h in bumps]
    vertices = []
    for v in directions:
        r = max(0.4, 1 + sum(h * math.exp(-12 * (1 - sum(a * b for a, b in zip(v, d)))) for d, h in bumps))
        stretch = (1.3, 1.0, 0.8)  # an elongated, flattish grain
        vertices.append(tuple(size / 2 * r * s * c for s, c in zip(stretch, v)))
    return vertices, faces


def torus(major, minor, around, across):
    vertices = []
    for i in range(around):
        for j in range(across):
            u, v = 2 * math.pi * i / around, 2 * math.pi * j / across
            vertices.append(((major + minor * math.cos(v)) * math.cos(u), (major + minor * math.cos(v)) * math.sin(u),
                             minor * math.sin(v)))
    at = lambda i, j: (i % around) * across + j % across
    faces = []
    for i in range(around):
        for j in range(across):
            faces.append((at(i, j), at(i + 1, j), at(i + 1, j + 1)))
            faces.append((at(i, j), at(i + 1, j + 1), at(i, j + 1)))
    return vertices, faces


def write_obj(path, vertices, faces, comment):
    with open(path, "w") as f:
        f.write(f"# {comment} (make_surface_meshes.py)\n")
        for v in vertices:
            f.write("v %.9g %.9g %.9g\n" % v)
        for a, b, c in faces:
            f.write(f"f {a + 1} {b + 1} {c + 1}\n")


if __name__ == "__main__":
    here = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).parent
    write_obj(here / "rock.obj", *rock(0.01), "a star-shaped, non-convex rock of 320 triangles, 13 mm long")
    write_obj(here / "ring.obj", *torus(0.01, 0.002, 24, 8), "a ring: torus of major radius 10 mm, tube 2 mm")
