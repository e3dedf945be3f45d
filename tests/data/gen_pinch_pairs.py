#!/usr/bin/python3
"""Generator of L-prism pairs whose overlap may be two pieces touching along an edge
(issue 54 point 10; tests/cli_pinch_pairs.sh). Usage:
    gen_pinch_pairs.py N SEED OUT      writes OUT.in.jsonl (queries) and OUT.truth.jsonl
MODE=sample: both inner corners on one line, axis-aligned poses (the shared degenerate
family's construction in other poses); ZMODES=a,b,...: the z-range relations drawn from
(same, a_in_b, b_in_a, partial, share_top).
Exact truth by construction: both prisms extruded along the same local axis (z);
the 2D cross-sections are L's (unions of two rectangles), B's mapped by an exact
integer (scaled) rotation / reflection about an anchor; truth = 2D exact
intersection (Fractions) x z-overlap, then an exact global pose (signed
permutation or integer-quaternion rotation, integer translation, 2^-k scale)."""
import json, random, sys, os
MODE = os.environ.get('MODE', '')
from fractions import Fraction as F
from itertools import combinations

TRIPLES = [(1, 0, 1), (3, 4, 5), (4, 3, 5), (5, 12, 13), (12, 5, 13), (8, 15, 17), (15, 8, 17), (7, 24, 25), (24, 7, 25)]

def l_outline(p, r, q1, q2):
    # CCW, reflex vertex at index 3 = (0,0); gap = open first quadrant
    return [(-p, -r), (q1, -r), (q1, 0), (0, 0), (0, q2), (-p, q2)]

def l_rects(p, r, q1, q2):
    return [[(-p, -r), (q1, -r), (q1, 0), (-p, 0)], [(-p, 0), (0, 0), (0, q2), (-p, q2)]]

def cross(o, a, b):
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

def area2(poly):
    return sum(poly[i][0] * poly[(i + 1) % len(poly)][1] - poly[(i + 1) % len(poly)][0] * poly[i][1] for i in range(len(poly)))

def clip(subject, clipper):  # convex CCW clipper, Sutherland-Hodgman, exact
    out = [tuple(map(F, v)) for v in subject]
    for i in range(len(clipper)):
        a, b = clipper[i], clipper[(i + 1) % len(clipper)]
        inp, out = out, []
        if not inp: break
        for j in range(len(inp)):
            P, Q = inp[j], inp[(j + 1) % len(inp)]
            sp, sq = cross(a, b, P), cross(a, b, Q)
            if sp >= 0: out.append(P)
            if (sp > 0 and sq < 0) or (sp < 0 and sq > 0):
                t = sp / (sp - sq)
                out.append((P[0] + t * (Q[0] - P[0]), P[1] + t * (Q[1] - P[1])))
    # drop duplicates / collinear
    res = []
    for v in out:
        if not res or res[-1] != v: res.append(v)
    while len(res) > 1 and res[0] == res[-1]: res.pop()
    changed = True
    while changed and len(res) >= 3:
        changed = False
        for i in range(len(res)):
            if cross(res[i - 1], res[i], res[(i + 1) % len(res)]) == 0:
                res.pop(i); changed = True; break
    return res if len(res) >= 3 and area2(res) > 0 else []

def share_segment(P, Q):
    for i in range(len(P)):
        a, b = P[i], P[(i + 1) % len(P)]
        for j in range(len(Q)):
            c, d = Q[j], Q[(j + 1) % len(Q)]
            if cross(a, b, c) != 0 or cross(a, b, d) != 0: continue
            dx, dy = b[0] - a[0], b[1] - a[1]
            pr = lambda v: (v[0] - a[0]) * dx + (v[1] - a[1]) * dy
            lo, hi = max(0, min(pr(c), pr(d))), min(dx * dx + dy * dy, max(pr(c), pr(d)))
            if hi > lo: return True
    return False

def truth2d(ra, rb):
    pieces = [x for A in ra for B in rb for x in [clip(A, B)] if x]
    par = list(range(len(pieces)))
    def f(i):
        while par[i] != i: i = par[i]
        return i
    for i, j in combinations(range(len(pieces)), 2):
        if share_segment(pieces[i], pieces[j]): par[f(i)] = f(j)
    comps = {}
    for i, pc in enumerate(pieces):
        a = area2(pc) / 2
        cx = sum((pc[k][0] + pc[(k + 1) % len(pc)][0]) * cross((0, 0), pc[k], pc[(k + 1) % len(pc)]) for k in range(len(pc))) / (6 * a)
        cy = sum((pc[k][1] + pc[(k + 1) % len(pc)][1]) * cross((0, 0), pc[k], pc[(k + 1) % len(pc)]) for k in range(len(pc))) / (6 * a)
        c = comps.setdefault(f(i), [F(0), F(0), F(0)])
        c[0] += a; c[1] += a * cx; c[2] += a * cy
    return [(a, mx / a, my / a) for a, mx, my in comps.values()]

def valid_diag(poly, i, j):
    n = len(poly)
    if (j - i) % n in (1, n - 1): return True
    a, b = poly[i], poly[j]
    for k in range(n):
        c, d = poly[k], poly[(k + 1) % n]
        if k in (i, j) or (k + 1) % n in (i, j):
            continue
        d1, d2, d3, d4 = cross(a, b, c), cross(a, b, d), cross(c, d, a), cross(c, d, b)
        if ((d1 > 0) != (d2 > 0) or d1 == 0 or d2 == 0) and ((d3 > 0) != (d4 > 0) or d3 == 0 or d4 == 0):
            if d1 == 0 and d2 == 0: continue
            return False
    # local inside test at a: b must lie in the interior cone at vertex i
    prv, nxt = poly[(i - 1) % n], poly[(i + 1) % n]
    if cross(prv, a, nxt) > 0:  # convex
        return cross(a, nxt, b) > 0 and cross(prv, a, b) > 0
    return not (cross(a, nxt, b) <= 0 and cross(prv, a, b) <= 0)

def triangulations(poly, idx):
    if len(idx) == 3: return [[tuple(idx)]]
    res = []
    a, b = idx[0], idx[1]
    for k in range(2, len(idx)):
        c = idx[k]
        if cross(poly[a], poly[b], poly[c]) <= 0: continue
        if not (valid_diag(poly, b, c) and valid_diag(poly, c, a)): continue
        left = [b] + idx[2:k + 1]  # polygon b..c
        right = [c] + idx[k + 1:] + [a]  # polygon c..a
        L = triangulations(poly, left) if len(left) >= 3 else [[]]
        R = triangulations(poly, right) if len(right) >= 3 else [[]]
        for x in L:
            for y in R: res.append([(a, b, c)] + x + y)
    return res

def quat_matrix(w, x, y, z):
    return [[w*w + x*x - y*y - z*z, 2*(x*y - w*z), 2*(x*z + w*y)],
            [2*(x*y + w*z), w*w - x*x + y*y - z*z, 2*(y*z - w*x)],
            [2*(x*z - w*y), 2*(y*z + w*x), w*w - x*x - y*y + z*z]], w*w + x*x + y*y + z*z

def det3(m):
    return (m[0][0]*(m[1][1]*m[2][2]-m[1][2]*m[2][1]) - m[0][1]*(m[1][0]*m[2][2]-m[1][2]*m[2][0]) + m[0][2]*(m[1][0]*m[2][1]-m[1][1]*m[2][0]))

def prism(outline2d, z0, z1, rng, info, tag):
    n = 6
    if area2(outline2d) < 0: outline2d = outline2d[::-1]
    s = rng.randrange(n)
    outline2d = outline2d[s:] + outline2d[:s]
    tris_all = triangulations(outline2d, list(range(n)))
    ti = rng.randrange(len(tris_all))
    cap = tris_all[ti]
    diag = [rng.randrange(2) for _ in range(n)]
    info[tag + '_cap'] = ti; info[tag + '_diag'] = ''.join(map(str, diag)); info[tag + '_start'] = s
    V = [(x, y, z0) for x, y in outline2d] + [(x, y, z1) for x, y in outline2d]
    T = []
    for (i, j, k) in cap: T.append((k, j, i))
    for (i, j, k) in cap: T.append((i + 6, j + 6, k + 6))
    for i in range(n):
        j = (i + 1) % n
        if diag[i] == 0: T += [(i, j, j + 6), (i, j + 6, i + 6)]
        else: T += [(i, j, i + 6), (j, j + 6, i + 6)]
    return V, T

def make_case(rng, idx):
    info = {}
    triple = rng.choice(TRIPLES[:1] * 4 + TRIPLES[1:]) if rng.random() < 0.9 else (1, 0, 1)
    a_, b_, c_ = triple
    quarter = rng.randrange(4)
    refl = rng.random() < 0.3
    kind = rng.choice(['RR', 'RR', 'RE', 'ER', 'any'])
    if MODE == 'sample': triple, a_, b_, c_, quarter, refl, kind = (1, 0, 1), 1, 0, 1, 2, False, 'RR'
    pa = [rng.randint(1, 12) for _ in range(4)]
    pb = [rng.randint(1, 12) for _ in range(4)]
    oa, ob = l_outline(*pa), l_outline(*pb)
    def edge_point(out, dims):
        p, r, q1, q2 = dims
        cands = []
        for i in range(6):
            u, v = out[i], out[(i + 1) % 6]
            L = abs(u[0] - v[0]) + abs(u[1] - v[1])
            for t in range(1, L):
                cands.append((u[0] + (v[0] - u[0]) * t // L, u[1] + (v[1] - u[1]) * t // L))
        return rng.choice(cands) if cands else (0, 0)
    anc_a = (0, 0) if kind in ('RR', 'RE') else edge_point(oa, pa) if kind == 'ER' else rng.choice(oa)
    anc_b = (0, 0) if kind in ('RR', 'ER') else edge_point(ob, pb) if kind == 'RE' else rng.choice(ob)
    info.update(kind=kind, pa=pa, pb=pb, anc_a=anc_a, anc_b=anc_b, triple=triple, quarter=quarter, refl=refl)
    # B map: w = M (v - anc_b) + c*anc_a ; A scaled by c
    ca, sa = a_, b_
    for _ in range(quarter): ca, sa = -sa, ca
    M = [[ca, -sa], [sa, ca]]
    if refl: M = [[M[0][0], M[0][1] * -1], [M[1][0], M[1][1] * -1]]  # v -> M diag(1,-1) v
    mapB = lambda v: (M[0][0] * (v[0] - anc_b[0]) + M[0][1] * (v[1] - anc_b[1]) + c_ * anc_a[0],
                      M[1][0] * (v[0] - anc_b[0]) + M[1][1] * (v[1] - anc_b[1]) + c_ * anc_a[1])
    mapA = lambda v: (c_ * v[0], c_ * v[1])
    A2 = [mapA(v) for v in oa]
    B2 = [mapB(v) for v in ob]
    ra = [[mapA(v) for v in R] for R in l_rects(*pa)]
    rb = []
    for R in l_rects(*pb):
        q = [mapB(v) for v in R]
        if area2(q) < 0: q = q[::-1]
        rb.append(q)
    comps = truth2d(ra, rb)
    # z ranges
    zmodes = os.environ.get('ZMODES', 'same,a_in_b,b_in_a,partial,partial,share_top').split(',')
    zmode = rng.choice(zmodes)
    za0 = rng.randint(-10, 0); za1 = za0 + rng.randint(2, 14)
    if zmode == 'same': zb0, zb1 = za0, za1
    elif zmode == 'a_in_b': zb0, zb1 = za0 - rng.randint(1, 5), za1 + rng.randint(1, 5)
    elif zmode == 'b_in_a':
        zb0 = za0 + rng.randint(1, (za1 - za0) // 2 if za1 - za0 >= 2 else 1); zb1 = rng.randint(zb0 + 1, za1 - 1) if za1 - 1 > zb0 else za1
    elif zmode == 'share_top': zb0, zb1 = za0 + rng.randint(1, za1 - za0 - 1), za1
    else:
        zb0 = rng.randint(za0 + 1, za1 - 1); zb1 = za1 + rng.randint(1, 6)
    if zmode != 'same' and (zb0 == za0 or zb1 == za1): zmode = 'share_top'  # a cap plane shared after all
    zs = c_
    za0, za1, zb0, zb1 = za0 * zs, za1 * zs, zb0 * zs, zb1 * zs
    zlen = max(0, min(za1, zb1) - max(za0, zb0)); zmid = F(max(za0, zb0) + min(za1, zb1), 2)
    info['zmode'] = zmode
    VA, TA = prism(A2, za0, za1, rng, info, 'a')
    VB, TB = prism(B2, zb0, zb1, rng, info, 'b')
    # global pose
    pose = rng.choice(['perm', 'perm', 'quat']) if MODE != 'sample' else 'perm'
    if pose == 'perm':
        perm = rng.sample(range(3), 3); sg = [rng.choice([-1, 1]) for _ in range(3)]
        G = [[sg[i] if perm[i] == j else 0 for j in range(3)] for i in range(3)]; gs = 1
    else:
        while True:
            q = [rng.randint(-3, 3) for _ in range(4)]
            if sum(x * x for x in q) > 1 and sum(1 for x in q if x) >= 2: break
        G, gs = quat_matrix(*q)
        if rng.random() < 0.3: G = [[-x for x in row] for row in G]
    info['pose'] = pose; info['G'] = G
    T = [rng.randint(-200, 200) * c_ * gs for _ in range(3)]
    k = rng.randint(0, 12)
    scale = F(1, 2 ** k) * rng.choice([1, 1, 1, 3, 5])
    info['k'] = k; info['T'] = T; info['scale'] = str(scale)
    apply = lambda v: tuple(float((sum(G[i][j] * v[j] for j in range(3)) + T[i]) * scale) for i in range(3))
    applyF = lambda v: [float((sum(G[i][j] * v[j] for j in range(3)) + T[i]) * scale) for i in range(3)]
    def mesh(V, Tr):
        W = [apply(v) for v in V]
        # exactness check
        for v, w in zip(V, W):
            for i in range(3):
                assert F(w[i]) == (sum(G[i][j] * v[j] for j in range(3)) + T[i]) * scale
        vol = sum(F(W[a][0]) * (F(W[b][1]) * F(W[c][2]) - F(W[b][2]) * F(W[c][1])) - F(W[a][1]) * (F(W[b][0]) * F(W[c][2]) - F(W[b][2]) * F(W[c][0])) + F(W[a][2]) * (F(W[b][0]) * F(W[c][1]) - F(W[b][1]) * F(W[c][0])) for a, b, c in Tr)
        if vol < 0: Tr = [(a, c, b) for a, b, c in Tr]
        return {"type": "mesh", "vertices": [list(w) for w in W], "triangles": [list(t) for t in Tr]}
    ma, mb = mesh(VA, TA), mesh(VB, TB)
    swap = rng.random() < 0.5
    info['swap'] = swap
    if swap: ma, mb = mb, ma
    vs = abs(det3(G)) * scale ** 3
    patches = sorted([{"volume": float(a * zlen * vs), "centroid": applyF((cx, cy, zmid))} for a, cx, cy in comps] if zlen > 0 else [], key=lambda p: -p["volume"])
    cid = f"pinch-{idx}-{kind}"
    return {"id": cid, "a": ma, "b": mb}, {"id": cid, "patches": patches, "info": info}

if __name__ == '__main__':
    n = int(sys.argv[1]); seed = int(sys.argv[2]); out = sys.argv[3]
    rng = random.Random(seed)
    with open(out + '.in.jsonl', 'w') as fi, open(out + '.truth.jsonl', 'w') as ft:
        for i in range(n):
            q, t = make_case(rng, i)
            fi.write(json.dumps(q) + '\n'); ft.write(json.dumps(t, default=str) + '\n')
