"""gjkdem.Surface from NumPy arrays: the overlap and distance of two closed
triangle surfaces, answers against closed forms and the swap property, and
bad arrays refused with ValueError (never a crash)."""
import numpy as np
import pytest

import gjkdem

CUBE_V = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], float)
CUBE_T = np.array([[0, 2, 1], [0, 3, 2], [4, 5, 6], [4, 6, 7], [0, 1, 5], [0, 5, 4],
                   [1, 2, 6], [1, 6, 5], [2, 3, 7], [2, 7, 6], [3, 0, 4], [3, 4, 7]])


def test_a_cube_has_its_mass_properties():
    s = gjkdem.Surface(CUBE_V * 2, CUBE_T)
    assert s.volume == pytest.approx(8, abs=1e-14)
    assert np.allclose(s.centroid, [1, 1, 1], atol=1e-14)
    assert s.triangle_count == 12 and s.vertex_count == 8


def test_two_cubes_overlap_in_a_corner_cube_both_ways():
    a = gjkdem.Surface(CUBE_V, CUBE_T)
    b = gjkdem.Surface(CUBE_V + [0.5, 0.25, 0.75], CUBE_T)
    o = gjkdem.surface_overlap(a, b)
    assert o.intersect
    assert o.volume == pytest.approx(0.5 * 0.75 * 0.25, abs=1e-15)
    assert np.allclose(o.centroid, [0.75, 0.625, 0.875], atol=1e-15)
    assert len(o.patches) == 1 and o.patches[0]["volume"] == pytest.approx(o.volume, abs=1e-15)
    s = gjkdem.surface_overlap(b, a)
    assert s.volume == pytest.approx(o.volume, abs=1e-15)
    assert np.allclose(s.area_a, o.area_b, atol=1e-15) and np.allclose(s.contact_normal, -o.contact_normal)


def test_apart_cubes_give_their_distance():
    a = gjkdem.Surface(CUBE_V, CUBE_T)
    b = gjkdem.Surface(CUBE_V + [3, 0, 0], CUBE_T)
    assert not gjkdem.surface_overlap(a, b).intersect
    d = gjkdem.surface_distance(a, b)
    assert d["distance"] == pytest.approx(2, abs=1e-14)
    assert d["witness_a"][0] == pytest.approx(1) and d["witness_b"][0] == pytest.approx(3)


@pytest.mark.parametrize("vertices, triangles, message", [
    (CUBE_V, CUBE_T[:-1], "only one triangle"),
    (CUBE_V, CUBE_T[:, ::-1], "face inward"),
    (CUBE_V, CUBE_T + 0.5, "indices of vertices"),
    (CUBE_V, -CUBE_T, "indices of vertices"),
    (CUBE_V, CUBE_T + 2**40, "indices of vertices"),
    (CUBE_V[:, :2], CUBE_T, r"shape \(N, 3\)"),
    (np.full((8, 3), np.inf), CUBE_T, "finite"),
    ("not an array", CUBE_T, "array"),
    (CUBE_V, [[0, 1]], r"shape \(N, 3\)"),
    (np.empty((0, 3)), np.empty((0, 3)), "at least 4 triangles"),
])
def test_bad_arrays_are_refused(vertices, triangles, message):
    with pytest.raises(ValueError, match=message):
        gjkdem.Surface(vertices, triangles)


def test_a_mesh_is_no_convex_shape():
    mesh = {"type": "mesh", "vertices": CUBE_V.tolist(), "triangles": CUBE_T.tolist()}
    with pytest.raises(ValueError, match="a mesh is a surface"):
        gjkdem.Shape.from_json(mesh)


def _prism(outline, cap, z0, z1):
    n = len(outline)
    v = [[x, y, z0] for x, y in outline] + [[x, y, z1] for x, y in outline]
    t = []
    for a, b, c in cap:
        t += [[a, c, b], [a + n, b + n, c + n]]
    for i in range(n):
        j = (i + 1) % n
        t += [[i, j, j + n], [i, j + n, i + n]]
    return np.array(v, float), np.array(t)


def _l_prism(rng):
    """An L-shaped prism on the integer grid, turned by a multiple of 90
    degrees, and the two boxes it is the union of."""
    a = rng.randint(2, 4); b = rng.randint(1, a - 1); d = rng.randint(2, 4); c = rng.randint(1, d - 1)
    x0, y0, z0 = rng.randint(0, 5), rng.randint(0, 5), rng.randint(0, 3)
    z1 = z0 + rng.randint(1, 3)
    turns = rng.randint(0, 3)

    def turned(p):
        x, y = p
        for _ in range(turns):
            x, y = -y, x
        return x0 + x, y0 + y

    outline = [turned(p) for p in [(0, 0), (a, 0), (a, c), (b, c), (b, d), (0, d)]]
    boxes = []
    for lo, hi in [((0, 0), (a, c)), ((0, c), (b, d))]:
        p, q = turned(lo), turned(hi)
        boxes.append(((min(p[0], q[0]), min(p[1], q[1]), z0), (max(p[0], q[0]), max(p[1], q[1]), z1)))
    v, t = _prism(outline, [(0, 1, 2), (0, 2, 3), (0, 3, 4), (0, 4, 5)], z0, z1)
    return gjkdem.Surface(v, t), boxes


def test_l_prisms_on_an_integer_grid_match_their_boxes():
    """Non-convex pairs full of coincidences (faces on one plane, edges on
    edges): the overlap is the sum of the overlaps of the boxes each L is
    made of."""
    import random
    rng = random.Random(3)
    for _ in range(600):
        (a, boxes_a), (b, boxes_b) = _l_prism(rng), _l_prism(rng)
        volume, moment = 0.0, np.zeros(3)
        for la, ha in boxes_a:
            for lb, hb in boxes_b:
                lo = np.maximum(la, lb); hi = np.minimum(ha, hb)
                v = float(np.prod(np.maximum(hi - lo, 0)))
                volume += v; moment += v * (lo + hi) / 2
        o = gjkdem.surface_overlap(a, b)
        assert o.volume == pytest.approx(volume, abs=1e-12)
        if volume > 0:
            assert np.allclose(o.centroid, moment / volume, atol=1e-12)
            assert sum(p["volume"] for p in o.patches) == pytest.approx(volume, abs=1e-12)


def l_prism(scale):
    """The L of [0,2]x[0,1] and [0,1]x[0,2], 1 thick, scaled, centred near the origin."""
    outline = [(0, 0), (2, 0), (2, 1), (1, 1), (1, 2), (0, 2)]
    cap = [(0, 1, 2), (0, 2, 3), (0, 3, 4), (0, 4, 5)]
    n = len(outline)
    v = [(x, y, 0) for x, y in outline] + [(x, y, 1) for x, y in outline]
    t = [f for a, b, c in cap for f in ((a, c, b), (a + n, b + n, c + n))]
    t += [f for i in range(n) for f in ((i, (i + 1) % n, (i + 1) % n + n), (i, (i + 1) % n + n, i + n))]
    return gjkdem.Surface((np.array(v, float) - [0.8, 0.8, 0.5]) * scale, np.array(t))


def test_surface_grains_settle_on_a_floor_in_a_world():
    s = gjkdem.Settings()
    s.model = "volume"
    b = gjkdem.WorldBuilder(s)
    b.add_material("rock", density=2500, youngs_modulus=1e7, restitution=0.3, friction=0.5)
    b.add_plane([0, 0, 0], [0, 0, 1], "rock")
    ell = l_prism(0.01)
    for k in range(3):
        b.add_body(ell, "rock", position=[0.002 * k, 0, 0.006 + 0.012 * k])
    w = b.build()
    assert w.template_count == 1  # one Surface object: one template
    assert w.masses()[0] == pytest.approx(2500 * 3e-6, rel=1e-12)  # the L's volume, not its hull's
    w.run(0.4, dt=5e-5)
    assert np.all(np.linalg.norm(w.velocities, axis=1) < 1e-3)
    assert np.all(w.positions[:, 2] > 0)  # resting on the floor, on each other
    assert len(w.contacts()["forces"]) >= 3


def test_a_compound_takes_surfaces_as_parts():
    """An L surface and a box filling its notch: the 2x2x1 box they make (mass
    properties of the solid, not of the hull), standing on a floor."""
    ell = l_prism(0.01)
    notch = gjkdem.Shape("box", half_extents=[0.005, 0.005, 0.005], center=[0.007, 0.007, 0.0])
    grain = gjkdem.Shape.compound([notch, ell])
    assert grain.parts == 2 and grain.type == "compound"
    assert grain.volume == pytest.approx(4e-6, rel=1e-12)
    assert np.allclose(grain.centroid, [0.002, 0.002, 0.0], atol=1e-15)
    with pytest.raises(ValueError, match="queries take one convex shape"):
        gjkdem.intersect(grain, notch)
    with pytest.raises(ValueError, match="gjkdem.Shape or gjkdem.Surface"):
        gjkdem.Shape.compound([notch, "not a part"])
    s = gjkdem.Settings()
    s.model = "volume"
    b = gjkdem.WorldBuilder(s)
    b.add_material("rock", density=2500, youngs_modulus=1e7, restitution=0.3, friction=0.5)
    b.add_plane([0, 0, 0], [0, 0, 1], "rock")
    b.add_body(grain, "rock", position=[0, 0, 0.0051])
    w = b.build()
    assert w.masses()[0] == pytest.approx(2500 * 4e-6, rel=1e-12)
    w.run(0.3, dt=5e-5)
    assert np.linalg.norm(w.velocities[0]) < 1e-3
    assert w.positions[0][2] == pytest.approx(0.005, abs=2e-4)  # on its face, 1 cm thick
    assert len(w.contacts()["forces"]) == 2  # the L's patch and the box's contact
    sunk = gjkdem.Shape.compound([gjkdem.Shape("box", half_extents=[0.005, 0.005, 0.005], center=[0.0, 0.0, 0.0]), ell])
    again = gjkdem.WorldBuilder(s)
    again.add_material("rock", density=2500, youngs_modulus=1e7)
    with pytest.raises(ValueError, match="parts 0 and 1 overlap"):
        again.add_body(sunk, "rock")


def test_surfaces_are_refused_where_they_cannot_go():
    b = gjkdem.WorldBuilder()
    b.add_material("rock", density=2500, youngs_modulus=1e7)
    with pytest.raises(ValueError, match="gjkdem.Shape, a gjkdem.Surface or a gjkdem.Shell"):
        b.add_body("not a shape", "rock")


def test_a_thin_shell_from_python():
    """A plate of two triangles, 2 mm thick: its volume, and it rests on a
    floor on its margin; bad shells and the places shells cannot go are
    refused with ValueError."""
    v = np.array([[-0.02, -0.02, 0], [0.02, -0.02, 0], [0.02, 0.02, 0], [-0.02, 0.02, 0]], float)
    t = np.array([[0, 1, 2], [0, 2, 3]])
    plate = gjkdem.Shell(v, t, 0.002)
    assert plate.volume == pytest.approx(0.04 * 0.04 * 0.002, rel=1e-12)
    assert plate.thickness == 0.002 and plate.triangle_count == 2
    with pytest.raises(ValueError, match="triangle 0 has no area"):
        gjkdem.Shell(np.array([[0, 0, 0], [1, 0, 0], [2, 0, 0]], float), np.array([[0, 1, 2]]), 0.002)
    with pytest.raises(ValueError, match="thickness must be > 0"):
        gjkdem.Shell(v, t, 0.0)
    s = gjkdem.Settings()
    s.model = "hertz"
    b = gjkdem.WorldBuilder(s)
    b.add_material("steel", density=7800, youngs_modulus=1e8, restitution=0.3, friction=0.3)
    b.add_plane([0, 0, 0], [0, 0, 1], "steel")
    b.add_body(plate, "steel", position=[0, 0, 0.004])
    with pytest.raises(ValueError, match="a body of its own"):
        b.fill_region([plate], 3, lo=[0, 0, 0.1], hi=[0.1, 0.1, 0.2], material="steel")
    w = b.build()
    assert w.masses()[0] == pytest.approx(7800 * 0.04 * 0.04 * 0.002, rel=1e-12)
    w.run(0.3, dt=2e-5)
    assert np.linalg.norm(w.velocities[0]) < 1e-3
    assert w.positions[0][2] == pytest.approx(0.001, abs=1e-4)  # on its margin
    volume = gjkdem.Settings()
    volume.model = "volume"
    v_builder = gjkdem.WorldBuilder(volume)
    v_builder.add_material("steel", density=7800, youngs_modulus=1e8)
    with pytest.raises(ValueError, match="thin shell takes the Hertz and linear laws"):
        v_builder.add_body(plate, "steel")
