# Generates tests/data/poly-hard.in.jsonl: polytope pairs harder than the shared
# sample; expected answers come from ../shared/tools/oracle.py (no GJK/EPA):
#   /usr/bin/python3 tests/data/gen_poly_hard.py 600 5 > tests/data/poly-hard.in.jsonl
#   /usr/bin/python3 ../shared/tools/oracle.py tests/data/poly-hard.in.jsonl -o tests/data/poly-hard.expected.jsonl --jobs 2
# Families: slivers and needles, nearly coplanar clouds, boxes rotated a hair
# face to face, vertex/edge contacts at gaps of +-1e-8 to 1e-4 of the size,
# duplicated vertices, offsets up to 1e6, sizes 1e-4 to 1e3, margins.
import json, math, random, sys
import numpy as np

rng = random.Random(int(sys.argv[2]) if len(sys.argv) > 2 else 5)

def rot():
    q = np.array([rng.gauss(0, 1) for _ in range(4)]); q /= np.linalg.norm(q)
    w, x, y, z = q
    return np.array([[1-2*(y*y+z*z), 2*(x*y-w*z), 2*(x*z+w*y)], [2*(x*y+w*z), 1-2*(x*x+z*z), 2*(y*z-w*x)],
                     [2*(x*z-w*y), 2*(y*z+w*x), 1-2*(x*x+y*y)]])

def cloud(family, size):
    n = rng.randint(4, 40)
    P = np.array([[rng.uniform(-1, 1) for _ in range(3)] for _ in range(n)])
    if family == 'sliver': P[:, 2] *= 10 ** rng.uniform(-9, -3)
    if family == 'needle': P[:, 1:] *= 10 ** rng.uniform(-9, -3)
    if family == 'box': P = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)], float) * [1, 0.7, 0.4]
    if family == 'dups': P = np.vstack([P, P[:n // 2], P[:3]])
    return (P @ rot().T) * size

def support(P, u):
    return P[np.argmax(P @ u)]

families = ['sliver', 'needle', 'box', 'dups', 'cloud']
n = int(sys.argv[1])
for i in range(n):
    fa, fb = rng.choice(families), rng.choice(families)
    size = 10 ** rng.uniform(-4, 3)
    A = cloud(fa, size)
    B = cloud(fb, size * rng.uniform(0.3, 2))
    u = np.array([rng.gauss(0, 1) for _ in range(3)]); u /= np.linalg.norm(u)
    gap = size * (10 ** rng.uniform(-8, -4)) * rng.choice([-1, 1]) if rng.random() < 0.7 else size * rng.uniform(-0.5, 0.3)
    t = u * (np.dot(support(A, u), u) - np.dot(support(B, -u), u) + gap)
    base = np.array([rng.uniform(-1, 1) for _ in range(3)]) * (1e6 if rng.random() < 0.2 else 10 * size)
    a = {"type": "polytope", "vertices": (A + base).tolist()}
    b = {"type": "polytope", "vertices": (B + base + t).tolist()}
    if rng.random() < 0.15: a["margin"] = size * rng.uniform(0, 0.05)
    print(json.dumps({"id": "poly-hard-%03d-%s-%s" % (i, fa, fb), "a": a, "b": b}))
