"""Generated hostile input for every Python surface (issue 32), bounded in
time and seeded: shapes and queries fed values of every type and nesting,
settings and builders fed wrong types and out-of-range numbers, scene text
mutated in its structure (tables, arrays, dotted keys), and view frames and
index files damaged byte by byte for both frame readers (Python's and the
C++ one behind gjkdem.analyze). Each call must return or raise an ordinary
exception; a crash or a hang ends the test process, which fails the test."""
import math
import random
import shutil
import time

import numpy as np
import pytest

import gjkdem

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")

BUDGET_S = 8.0  # per test: the loops stop early rather than outlast it (once they have tried the least they assert)

JUNK = [None, True, -1, 0, 2**64, 10**400, -0.0, 1e308, -1e308, float("nan"), float("inf"), 1e-320, "x", "",
        [], {}, [1.0], [1.0, 2.0], [[1.0, 2.0, 3.0]], {"a": 1}, b"\x00", (1, 2, 3), object()]


def deep(levels):
    nested = [0.0]
    for _ in range(levels):
        nested = [nested]
    return nested


def looped():
    it = []
    it.append(it)
    return it


def junk(rng, depth=0):
    """A value of any type: numbers, strings, lists and dicts, nested a few
    levels, and now and then nested tens of thousands deep or holding itself."""
    if depth == 0 and rng.random() < 0.01:
        return rng.choice([deep(rng.randrange(60, 70)), deep(50000), looped()])
    k = rng.randrange(6)
    if depth < 3 and k == 0:
        return [junk(rng, depth + 1) for _ in range(rng.randrange(5))]
    if depth < 3 and k == 1:
        return {rng.choice(["radius", "center", "vertices", "type", "margin", "x"]): junk(rng, depth + 1)
                for _ in range(rng.randrange(4))}
    if k == 2:
        return np.asarray(rng.random() * 10 - 5) * np.ones(tuple(rng.randrange(0, 4) for _ in range(rng.randrange(3))))
    return rng.choice(JUNK)


def ordinary(call):
    """Runs call; what it may raise is an ordinary exception (never a crash)."""
    try:
        call()
        return True
    except (ValueError, TypeError, RuntimeError, OverflowError, KeyError, IndexError, MemoryError):
        return False


FIELDS = {
    "sphere": ["radius", "center", "margin"], "box": ["half_extents", "center", "rotation", "margin"],
    "polytope": ["vertices", "margin"], "cylinder": ["radius", "half_height", "center", "rotation"],
    "ellipsoid": ["radii", "center"], "capsule": ["a", "b", "radius"], "triangle": ["vertices", "margin"],
    "superellipsoid": ["radii", "exponents", "center"], "cone": ["radius", "half_height", "center"],
}


def test_shapes_and_queries_take_any_value():
    rng = random.Random(7)
    good = gjkdem.Shape("box", half_extents=[0.5, 0.5, 0.5])
    end, made = time.monotonic() + BUDGET_S, 0
    while made <= 100 or (time.monotonic() < end and made < 3000):
        kind = rng.choice(list(FIELDS) + ["nope", ""])
        fields = {f: junk(rng) for f in FIELDS.get(kind, ["radius"]) if rng.random() < 0.8}
        shape = []
        ordinary(lambda: shape.append(gjkdem.Shape(kind, **fields)))
        ordinary(lambda: gjkdem.Shape.from_json(junk(rng)))
        other = shape[0] if shape else good
        pose = junk(rng) if rng.random() < 0.5 else [rng.uniform(-2, 2), 0, 0, 1, 0, 0, 0]
        for query in (gjkdem.intersect, gjkdem.distance, gjkdem.penetration):
            ordinary(lambda: query(good, other, None, pose))
        poses = junk(rng) if rng.random() < 0.3 else np.zeros((rng.randrange(0, 4), 7)) + [0, 0, 0, 1, 0, 0, 0]
        ordinary(lambda: gjkdem.distance_batch(good, [other] * rng.randrange(0, 3), poses, None))
        made += 1
    assert made > 100


def test_settings_and_builders_take_any_value():
    rng = random.Random(11)
    names = ["model", "gravity", "linear_stiffness", "volume_stiffness", "volume_form", "rocking_resistance",
             "tessellation", "box_skin", "threads", "periodic", "cell_control"]
    end, tried = time.monotonic() + BUDGET_S, 0
    while tried <= 100 or (time.monotonic() < end and tried < 2000):  # at least 101, whatever the load
        s = gjkdem.Settings()
        for _ in range(rng.randrange(1, 4)):
            ordinary(lambda: setattr(s, rng.choice(names), junk(rng)))
        b = []
        if ordinary(lambda: b.append(gjkdem.WorldBuilder(s))):
            builder = b[0]
            ordinary(lambda: builder.add_material(junk(rng) if rng.random() < 0.2 else "m", junk(rng), junk(rng)))
            ordinary(lambda: builder.add_material("ok", 2500, 1e7))
            ordinary(lambda: builder.add_plane(junk(rng), junk(rng), "ok"))
            ordinary(lambda: builder.add_body(gjkdem.Shape("sphere", radius=0.01), "ok", position=junk(rng)))
            ordinary(lambda: builder.fill_region(gjkdem.Shape("sphere", radius=0.01), junk(rng), [-0.1, -0.1, 0],
                                                 [0.1, 0.1, 0.2], "ok"))
            ordinary(builder.build)
        tried += 1
    assert tried > 100


SCENE = """[simulation]
duration = 0.001
[contact]
model = "hertz"
[[material]]
name = "m"
density = 2500.0
youngs_modulus = 1.0e7
[[wall]]
type = "plane"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
material = "m"
[[generator]]
count = 5
material = "m"
region = { min = [-0.05, -0.05, 0.0], max = [0.05, 0.05, 0.1] }
shape = { type = "sphere", radius = 0.005 }
"""

PIECES = ["[", "]", "[[", "]]", "{", "}", "=", ",", ".", "\n", '"', "'", "#", "a.b.c", "[x.y]", "1e999", "nan",
          "[[material]]", "{ type = 1 }", "[1, [2, [3]]]", "\"\\u0000\"", "x = { a = { b = { c = 1 } } }"]


def test_scene_text_mutated_in_its_structure_is_refused_or_read():
    rng = random.Random(13)
    end, tried = time.monotonic() + BUDGET_S, 0
    while tried <= 100 or (time.monotonic() < end and tried < 3000):
        text = SCENE
        for _ in range(rng.randrange(1, 4)):
            i = rng.randrange(len(text))
            k = rng.randrange(4)
            if k == 0:
                text = text[:i] + rng.choice(PIECES) + text[i:]
            elif k == 1:
                text = text[:i] + text[i + rng.randrange(1, 20):]
            elif k == 2:  # a line repeated or moved
                lines = text.splitlines(True)
                j = rng.randrange(len(lines))
                lines.insert(rng.randrange(len(lines)), lines[j])
                text = "".join(lines)
            else:  # a key nested deeper: a little, or tens of thousands of levels
                levels = rng.randrange(1, 80) if rng.random() < 0.95 else 50000
                text = text[:i] + "." + "d." * levels + "e" + text[i:]
        try:
            gjkdem.load_scene_text(text)
        except (gjkdem.SceneError, ValueError, UnicodeError):
            pass
        tried += 1
    assert tried > 100


@pytest.fixture(scope="module")
def small_run(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("fuzz_run")
    (tmp / "scene.toml").write_text(SCENE.replace("duration = 0.001", "duration = 0.01"))
    out = tmp / "out"
    assert gjkdem.SceneRun(str(tmp / "scene.toml"), out=str(out), threads=1).run() == "completed"
    return out


def test_damaged_frames_and_indexes_are_refused_by_both_readers(small_run, tmp_path):
    rng = random.Random(17)
    frame_file = small_run / "view" / "frame_000001.bin"
    frame = frame_file.read_bytes()
    index = (small_run / "view" / "index.csv").read_text()
    end, tried = time.monotonic() + BUDGET_S, 0
    while tried <= 5 or (time.monotonic() < end and tried < 60):
        data = bytearray(frame)
        for _ in range(rng.randrange(1, 6)):
            k = rng.randrange(3)
            if k == 0:
                data[rng.randrange(len(data))] = rng.randrange(256)
            elif k == 1:
                i = rng.randrange(len(data))
                data[i:i + 4] = rng.choice([b"\xff\xff\xff\xff", b"\x00\x00\xc0\x7f", b"\x00\x00\x80\x7f"])
            else:
                del data[rng.randrange(len(data)):]
        ordinary(lambda: gjkdem.view.Frame(bytes(data)))
        damaged = tmp_path / f"run{tried}"
        shutil.copytree(small_run, damaged)
        (damaged / "view" / "frame_000001.bin").write_bytes(bytes(data))
        if rng.random() < 0.5:
            lines = index.splitlines()
            j = rng.randrange(1, len(lines))
            cut = rng.randrange(len(lines[j]) + 1)
            lines[j] = lines[j][:cut] + rng.choice(["x", ",", "-1", "nan", "99999999999999999999", ""]) + lines[j][cut:]
            (damaged / "view" / "index.csv").write_text("\n".join(lines) + "\n")
        ordinary(lambda: [v.frame(k) for v in [gjkdem.read_view(damaged)] for k in range(len(v))])
        ordinary(lambda: gjkdem.analyze(str(damaged)))
        measures = damaged / "analysis" / "measures.csv"
        if measures.exists():  # what was written holds finite numbers only
            for row in measures.read_text().splitlines()[1:]:
                assert all(math.isfinite(float(x)) for x in row.split(",")), row
        shutil.rmtree(damaged)
        tried += 1
    assert tried > 5
