# Generates tests/data/curved-hard.in.jsonl (seed 11, 800 pairs); expected answers come from
# ../shared/tools/oracle.py (independent of GJK/EPA):
#   /usr/bin/python3 tests/data/gen_curved_hard.py 800 11 > tests/data/curved-hard.in.jsonl
#   /usr/bin/python3 ../shared/tools/oracle.py tests/data/curved-hard.in.jsonl -o tests/data/curved-hard.expected.jsonl --jobs 2
# Harder than the shared sample: exponents near 0.3 and 2, aspect ratios to 20, gaps of 1e-7 to 1e-3
# of the size, deep overlaps, offsets to 1e5.
import json, math, os, random, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '../../../shared/tools'))
import numpy as np
import curved
rng = random.Random(int(sys.argv[2]) if len(sys.argv) > 2 else 7)
def quat():
    q = [rng.gauss(0,1) for _ in range(4)]; n = math.sqrt(sum(x*x for x in q)); return [x/n for x in q]
def shape(kind, size):
    c = [0,0,0]
    if kind == 'ellipsoid':
        r = [size*rng.uniform(0.05,1) for _ in range(3)]; return {"type":"ellipsoid","center":c,"radii":r,"rotation":quat()}
    if kind == 'superellipsoid':
        ex = [rng.choice([rng.uniform(0.25,0.35), rng.uniform(1.85,2.0), rng.uniform(0.3,2)]) for _ in range(2)]
        r = [size*rng.uniform(0.1,1) for _ in range(3)]; return {"type":"superellipsoid","center":c,"radii":r,"exponents":ex,"rotation":quat()}
    if kind == 'cylinder':
        return {"type":"cylinder","center":c,"radius":size*rng.uniform(0.05,1),"half_height":size*rng.uniform(0.02,1),"rotation":quat()}
    if kind == 'cone':
        return {"type":"cone","center":c,"radius":size*rng.uniform(0.05,1),"half_height":size*rng.uniform(0.05,1),"rotation":quat()}
    if kind == 'box':
        return {"type":"box","center":c,"half_extents":[size*rng.uniform(0.05,1) for _ in range(3)],"rotation":quat()}
    if kind == 'sphere':
        return {"type":"sphere","center":c,"radius":size*rng.uniform(0.1,1)}
    if kind == 'capsule':
        d = np.array([rng.gauss(0,1) for _ in range(3)]); d = d/np.linalg.norm(d)*size*rng.uniform(0.1,1)
        return {"type":"capsule","p0":list(-d),"p1":list(d),"radius":size*rng.uniform(0.05,0.5)}
    if kind == 'polytope':
        return {"type":"polytope","vertices":[[size*rng.uniform(-1,1) for _ in range(3)] for _ in range(rng.randint(4,20))]}
def moved(s, t):
    s = json.loads(json.dumps(s))
    if 'center' in s: s['center'] = list(np.array(s['center']) + t)
    if 'p0' in s: s['p0'] = list(np.array(s['p0']) + t); s['p1'] = list(np.array(s['p1']) + t)
    if 'vertices' in s: s['vertices'] = [list(np.array(v) + t) for v in s['vertices']]
    return s
curved_kinds = ['ellipsoid','superellipsoid','cylinder','cone']
all_kinds = curved_kinds + ['box','sphere','capsule','polytope']
n = int(sys.argv[1])
for i in range(n):
    ka = rng.choice(curved_kinds); kb = rng.choice(all_kinds)
    size = 10 ** rng.uniform(-2, 2)
    a = shape(ka, size); b = shape(kb, size * rng.uniform(0.2, 2))
    if rng.random() < 0.3: a['margin'] = size * rng.uniform(0.001, 0.1)
    if rng.random() < 0.3 and kb != 'sphere': b['margin'] = size * rng.uniform(0.001, 0.1)
    u = np.array([rng.gauss(0,1) for _ in range(3)]); u /= np.linalg.norm(u)
    A = curved.Shape(a); B = curved.Shape(b)
    ha = A.h(u[None,:])[0]; hb = B.h(-u[None,:])[0]
    mode = rng.random()
    gap = size * (10 ** rng.uniform(-7, -3)) * (1 if rng.random() < 0.5 else -1) if mode < 0.6 else size * rng.uniform(-0.8, 0.3)
    t = u * (ha + hb + gap)
    base = np.array([rng.uniform(-1,1) for _ in range(3)]) * size * (1e4 if rng.random() < 0.1 else 5)
    rec = {"id": "hard-%03d-%s-%s" % (i, ka, kb), "a": moved(a, base), "b": moved(b, base + t)}
    print(json.dumps(rec))
