"""Queries from Python against the C++ program on the shared pair samples,
the batched forms against the single ones, and the properties every query
keeps (A and B swapped, translated)."""
import json
import subprocess

import numpy as np
import pytest

import gjkdem


def read_pairs(path):
    pairs = []
    for line in path.read_text().splitlines():
        if line.strip() and not line.startswith("#"):
            pairs.append(json.loads(line))
    return pairs


def cli_answers(cli, path):
    run = subprocess.run([cli, "query", "--in", str(path)], capture_output=True, text=True)
    assert run.returncode in (0, 1), run.stderr
    return [json.loads(line) for line in run.stdout.splitlines()]


def test_every_shared_sample_gives_the_programs_answer(cli, pairs_dir):
    files = sorted(pairs_dir.glob("*.in.jsonl"))
    assert files, "no samples"
    compared = 0
    for path in files:
        for pair, expected in zip(read_pairs(path), cli_answers(cli, path)):
            assert expected["id"] == pair["id"]
            if "error" in expected:
                with pytest.raises(ValueError):
                    gjkdem.penetration(gjkdem.Shape.from_json(pair["a"]), gjkdem.Shape.from_json(pair["b"]))
                continue
            a, b = gjkdem.Shape.from_json(pair["a"]), gjkdem.Shape.from_json(pair["b"])
            r = gjkdem.penetration(a, b)
            what = f"{path.name} {pair['id']}"
            # The same code on the same numbers: the same bits (the program prints numbers that read back exactly).
            assert r.intersect == expected["intersect"], what
            assert r.distance == expected["distance"], what
            assert r.depth == expected["depth"], what
            assert list(r.normal) == expected["normal"], what
            assert list(r.witness_a) == expected["witness_a"], what
            assert gjkdem.intersect(a, b) == expected["intersect"], what  # touching pairs included
            compared += 1
    assert compared > 500


def random_polytope(rng, n=12):
    return gjkdem.Shape("polytope", vertices=rng.normal(size=(n, 3)))


def random_poses(rng, n, spread=3.0):
    q = rng.normal(size=(n, 4))
    q /= np.linalg.norm(q, axis=1)[:, None]
    return np.hstack([rng.uniform(-spread, spread, size=(n, 3)), q])


def test_batches_give_the_single_answers_for_any_thread_count():
    rng = np.random.default_rng(7)
    a = [random_polytope(rng) for _ in range(300)]
    b = gjkdem.Shape("ellipsoid", radii=[1.0, 0.5, 0.7], margin=0.05)
    pa, pb = random_poses(rng, 300), random_poses(rng, 300)
    one = gjkdem.penetration_batch(a, b, pa, pb, threads=1)
    two = gjkdem.penetration_batch(a, b, pa, pb, threads=2)
    for key in one:
        assert np.array_equal(one[key], two[key]), key
    for k in range(0, 300, 7):
        r = gjkdem.penetration(a[k], b, pa[k], pb[k])
        assert one["intersect"][k] == r.intersect
        assert one["distance"][k] == r.distance and one["depth"][k] == r.depth
        assert np.array_equal(one["normal"][k], r.normal)
    hits = gjkdem.intersect_batch(a, b, pa, pb)["intersect"]
    assert np.array_equal(hits, one["intersect"])
    assert 0 < hits.sum() < 300
    d = gjkdem.distance_batch(a, b, pa, pb)
    assert np.array_equal(d["distance"], one["distance"])


def test_shape_sets_give_the_lists_answers():
    rng = np.random.default_rng(9)
    # Shapes whose frames differ from the user's (a box off its centre, a
    # polytope about its centroid) check that the offsets go with the set.
    a = [random_polytope(rng) for _ in range(150)] + [gjkdem.Shape("box", half_extents=[0.5, 0.3, 0.2])]
    b = [random_polytope(rng, 6) for _ in range(151)]
    pa, pb = random_poses(rng, 151), random_poses(rng, 151)
    sa, sb = gjkdem.ShapeSet(a), gjkdem.ShapeSet(b)
    assert len(sa) == 151
    for batch in (gjkdem.intersect_batch, gjkdem.distance_batch, gjkdem.penetration_batch, gjkdem.overlap_batch):
        lists, sets = batch(a, b, pa, pb), batch(sa, sb, pa, pb)
        for key in lists:
            assert np.array_equal(lists[key], sets[key], equal_nan=True), (batch.__name__, key)
    # A set against one shape, without poses for the set.
    mixed = gjkdem.penetration_batch(sa, b[0], None, pb)
    assert np.array_equal(mixed["depth"], gjkdem.penetration_batch(a, b[0], None, pb)["depth"])
    with pytest.raises(ValueError, match="ShapeSet"):
        gjkdem.ShapeSet([a[0], "rock"])
    with pytest.raises(ValueError, match="empty"):
        gjkdem.ShapeSet([])
    with pytest.raises(ValueError, match="compound"):
        gjkdem.ShapeSet([gjkdem.Shape.compound([gjkdem.Shape("sphere", radius=0.1),
                                                gjkdem.Shape("sphere", radius=0.1, center=[1, 0, 0])])])
    with pytest.raises(ValueError, match="one entry per pair"):
        gjkdem.intersect_batch(sa, gjkdem.ShapeSet(b[:10]))


def test_overlap_batch_matches_single_overlaps_and_marks_empty_rows():
    rng = np.random.default_rng(3)
    a = [random_polytope(rng) for _ in range(100)]
    box = gjkdem.Shape("box", half_extents=[1.0, 1.0, 1.0])
    pa = random_poses(rng, 100, spread=2.0)
    out = gjkdem.overlap_batch(a, box, pa, None)
    for k in range(100):
        r = gjkdem.overlap(a[k], box, pa[k])
        assert out["volume"][k] == r.volume
        if r.centroid is None:
            assert np.isnan(out["centroid"][k]).all()
        else:
            assert np.array_equal(out["centroid"][k], r.centroid)
    assert (out["volume"] > 0).any() and (out["volume"] == 0).any()


def test_swapping_a_and_b_mirrors_the_answer():
    rng = np.random.default_rng(11)
    for _ in range(200):
        a, b = random_polytope(rng), gjkdem.Shape("cylinder", radius=0.6, half_height=0.9, margin=0.02)
        pa, pb = random_poses(rng, 2, spread=1.5)
        ab, ba = gjkdem.penetration(a, b, pa, pb), gjkdem.penetration(b, a, pb, pa)
        assert ab.intersect == ba.intersect
        scale = max(1.0, ab.distance + ab.depth)
        assert abs(ab.distance - ba.distance) <= 1e-9 * scale
        assert abs(ab.depth - ba.depth) <= 1e-7 * scale
        if ab.distance > 1e-6:
            assert np.allclose(ab.normal, -ba.normal, atol=1e-4)  # GJK's tolerance on the distance


def test_a_translation_of_1e6_keeps_the_answer():
    rng = np.random.default_rng(5)
    shift = np.array([1e6, -1e6, 1e6, 0, 0, 0, 0])
    for _ in range(100):
        a, b = random_polytope(rng), gjkdem.Shape("sphere", radius=0.7)
        pa, pb = random_poses(rng, 2, spread=1.5)
        near, far = gjkdem.penetration(a, b, pa, pb), gjkdem.penetration(a, b, pa + shift, pb + shift)
        assert near.intersect == far.intersect
        assert abs(near.distance - far.distance) < 1e-8 and abs(near.depth - far.depth) < 1e-8


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda s: gjkdem.distance(s, s, [0, 0, 0, 2, 0, 0, 0]), "pose_a: quaternion [w, x, y, z] must be unit"),
        (lambda s: gjkdem.distance(s, s, [0, 0, float("nan"), 1, 0, 0, 0]), "NaN or infinite number"),
        (lambda s: gjkdem.distance(s, s, None, [0, 0, 0]), "pose_b [x, y, z, qw, qx, qy, qz]: expected 7 numbers"),
        (lambda s: gjkdem.distance(s, s, "here"), "pose_a [x, y, z, qw, qx, qy, qz]: expected"),
        (lambda s: gjkdem.distance_batch(s, s, np.zeros((4, 6))), "poses_a: expected an array of shape (N, 7)"),
        (lambda s: gjkdem.distance_batch(s, s, np.zeros((4, 7))), "poses_a[0]: quaternion"),
        (lambda s: gjkdem.distance_batch([s, s], s, None, np.tile([0, 0, 0, 1, 0, 0, 0], (3, 1))),
         "one entry per pair (got 2 and 3)"),
        (lambda s: gjkdem.distance_batch(s, s), "give poses as (N, 7) arrays"),
        (lambda s: gjkdem.distance_batch([s, 3], s), "a: expected a gjkdem.Shape or a list of them"),
        (lambda s: gjkdem.distance_batch(s, s, np.tile([0, 0, 0, 1, 0, 0, 0], (3, 1)), threads=-1),
         "threads: must be >= 0"),
        (lambda s: gjkdem.Shape("sphere", radius=float("nan")), "radius: NaN or infinite number"),
        (lambda s: gjkdem.Shape("sphere", radius=-1.0), "radius must be >= 0"),
        (lambda s: gjkdem.Shape("blob", radius=1.0), "blob"),
        (lambda s: gjkdem.Shape("box", half_extents=[1, 1]), "half_extents"),
        (lambda s: gjkdem.Shape.from_json("{not json"), "shape is not valid JSON"),
    ],
)
def test_bad_input_raises_value_error_with_its_message(call, message):
    with pytest.raises(ValueError) as e:
        call(gjkdem.Shape("box", half_extents=[1.0, 1.0, 1.0]))
    assert message in str(e.value)


def test_shapes_keep_the_frame_they_were_given_in():
    cube = np.array([[x, y, z] for x in (4, 6) for y in (4, 6) for z in (4, 6)], dtype=float)
    p = gjkdem.Shape("polytope", vertices=cube)
    assert np.allclose(p.centroid, [5, 5, 5]) and p.volume == pytest.approx(8)
    box = gjkdem.Shape("box", half_extents=[1, 1, 1])
    d = gjkdem.distance(p, box, None, [5, 5, 8, 1, 0, 0, 0])
    assert d.distance == pytest.approx(1.0)


def test_triangle_distances_match_gjk_on_each_pair():
    rng = np.random.default_rng(17)
    n = 203  # not a multiple of the kernel's block
    a = rng.uniform(-1, 1, size=(n, 3, 3))
    b = rng.uniform(-1, 1, size=(n, 3, 3)) + rng.uniform(-0.8, 0.8, size=(n, 1, 3))
    out = gjkdem.triangle_distances(a, b)
    assert out["distance"].shape == (n,) and out["witness_a"].shape == (n, 3)
    touching = 0
    for k in range(n):
        r = gjkdem.distance(gjkdem.Shape("triangle", vertices=a[k]), gjkdem.Shape("triangle", vertices=b[k]))
        want = 0.0 if r.intersect else r.distance
        assert abs(out["distance"][k] - want) < 1e-9, k
        assert abs(np.linalg.norm(out["witness_b"][k] - out["witness_a"][k]) - out["distance"][k]) < 1e-12
        touching += out["distance"][k] == 0
    assert 10 < touching < n - 10  # both kinds of pairs occur


def test_triangle_distances_refuse_bad_arrays():
    good = np.zeros((2, 3, 3))
    assert gjkdem.triangle_distances(np.zeros((0, 3, 3)), np.zeros((0, 3, 3)))["distance"].shape == (0,)
    for bad, words in [(np.zeros((2, 3)), r"shape \(N, 3, 3\)"), (np.zeros((3, 3, 3)), "one pair per row"),
                       ("text", r"shape \(N, 3, 3\)")]:
        with pytest.raises(ValueError, match=words):
            gjkdem.triangle_distances(good, bad)
    nan = good.copy()
    nan[1, 2, 0] = np.nan
    with pytest.raises(ValueError, match="triangle 1 has a coordinate that is not finite"):
        gjkdem.triangle_distances(nan, good)
