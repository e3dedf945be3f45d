"""examples/python/repose_study.py: a heap's angle of repose from a lifted
cylinder, at two frictions from one settled bed. heap_angle is checked on
heaps whose angle is known by construction (grains filling a cone); the
study itself runs end to end on a few grains (its numbers mean little there:
tests check that each friction's run starts from the one settled bed, lifts
the cylinder and writes the table)."""
import csv
import math
import pathlib
import sys

import numpy as np
import pytest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "examples" / "python"))
import repose_study  # noqa: E402


def cone_heap(angle_deg, radius, count, seed):
    """Grain centres uniform in a cone of base `radius` whose flank rises at angle_deg, axis at (0.2, -0.1)."""
    rng = np.random.default_rng(seed)
    height = radius * math.tan(math.radians(angle_deg))
    points = []
    while len(points) < count:
        x, y = rng.uniform(-radius, radius, 2)
        z = rng.uniform(0, height)
        if math.hypot(x, y) <= radius * (1 - z / height):
            points.append((x + 0.2, y - 0.1, z))
    return np.array(points)


@pytest.mark.parametrize("angle", [20.0, 30.0, 38.0])
def test_heap_angle_finds_the_angle_of_a_cone(angle):
    measured, radius, height = repose_study.heap_angle(cone_heap(angle, 0.05, 6000, seed=int(angle)))
    assert measured == pytest.approx(angle, abs=1.5)
    # The 95th percentile of the distances from the axis: in a full cone of base R,
    # the fraction within r is 3 (r/R)^2 - 2 (r/R)^3, 0.95 at r = 0.8647 R.
    assert radius == pytest.approx(0.8647 * 0.05, rel=0.02)
    assert height == pytest.approx(0.05 * math.tan(math.radians(angle)), rel=0.1)


def test_heap_angle_refuses_too_few_grains():
    with pytest.raises(ValueError, match="at least 10 grains"):
        repose_study.heap_angle(np.zeros((3, 3)))


def test_the_study_runs_from_one_settled_bed(tmp_path):
    rows = repose_study.main(["--grains", "40", "--frictions", "0.2", "0.9", "--settle", "0.15", "--rest", "0.05",
                              "--lift-speed", "1.0", "--out", str(tmp_path), "--quiet"])
    assert [r[0] for r in rows] == [0.2, 0.9]
    table = list(csv.DictReader(open(tmp_path / "repose.csv")))
    assert [float(r["friction"]) for r in table] == [0.2, 0.9]
    assert all(0 <= float(r["angle_deg"]) < 90 for r in table)
    import json
    for name in ("friction_0.2", "friction_0.9"):
        info = json.loads((tmp_path / name / "run.json").read_text())
        assert info["status"] == "completed"
        assert info["started_from"] == str((tmp_path / "settle").resolve())
