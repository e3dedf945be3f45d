"""examples/python/drum_angle.py measures a drum's dynamic angle of repose
(docs/dem.md). Checked here on beds whose angle is known by construction:
grains scattered uniformly over the part of the drum's section below a line
through the axis inclined at theta (a half-full drum with a flat surface),
for which both the strips' top heights and the centroid give theta."""
import math
import pathlib
import sys

import numpy as np
import pytest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "examples" / "python"))
import drum_angle  # noqa: E402

RADIUS = 0.069


def half_full_bed(theta_deg, count, seed, length=0.1):
    """Grains (x, y, z) uniform in the half disc below z = tan(theta) x, y along the axis."""
    rng = np.random.default_rng(seed)
    r = RADIUS * np.sqrt(rng.uniform(0, 1, 4 * count))
    a = rng.uniform(0, 2 * math.pi, 4 * count)
    x, z = r * np.cos(a), r * np.sin(a)
    t = math.tan(math.radians(theta_deg))
    below = z < t * x
    x, z = x[below][:count], z[below][:count]
    y = rng.uniform(-length / 2, length / 2, count)
    return np.column_stack([x, y, z])


@pytest.mark.parametrize("theta", [15.0, 26.0, 35.0])
def test_a_flat_surface_gives_its_angle(theta):
    p = half_full_bed(theta, 40000, seed=int(theta))
    surface = drum_angle.surface_angle(p[:, 0], p[:, 2], RADIUS)
    # The mean of the 10 highest grains of a strip sits a little below the
    # line, by the same amount in every strip: the slope is kept.
    assert abs(surface - theta) < 0.5
    centroid = math.degrees(math.atan2(abs(p[:, 0].mean()), -p[:, 2].mean()))
    assert abs(centroid - theta) < 0.5


def test_an_npz_of_frames_is_measured_like_a_run(tmp_path, capsys):
    times = np.array([1.0, 1.5, 2.0])
    frames = np.array([half_full_bed(30.0, 20000, seed=k) for k in range(3)])
    path = tmp_path / "other_code.npz"
    np.savez(path, times=times, frames=frames)
    drum_angle.main([str(path), "--radius", str(RADIUS), "--from", "1.5"])
    out = capsys.readouterr().out
    assert "frames 2, from t = 1.5 s" in out
    surface = float(out.split("free surface:")[1].split()[0])
    assert abs(surface - 30.0) < 0.5
    # A band along the axis keeps only its grains, and an empty range of times is refused.
    drum_angle.main([str(path), "--radius", str(RADIUS), "--from", "1.0", "--band", "0.0", "0.05"])
    assert "frames 3" in capsys.readouterr().out
    with pytest.raises(SystemExit):
        drum_angle.main([str(path), "--radius", str(RADIUS), "--from", "5"])


def test_what_cannot_be_read_is_named_in_one_line(tmp_path):
    not_npz = tmp_path / "garbage.npz"
    not_npz.write_text("garbage")
    no_frames = tmp_path / "no_frames.npz"
    np.savez(no_frames, times=np.array([1.0]))
    for path in (not_npz, no_frames, tmp_path / "no_run"):
        with pytest.raises(SystemExit) as e:
            drum_angle.main([str(path), "--radius", str(RADIUS)])
        assert str(e.value).startswith(f"drum_angle.py: cannot read {path}: "), e.value


def test_the_drum_torque_counts_the_fixed_pieces_forces_on_grains():
    class Frame:  # the fields drum_angle reads of a gjkdem.view Frame
        pass

    f = Frame()
    f.flags = np.array([1, 0, 0, 1], np.uint8)  # bodies 0 and 3 are drum pieces
    plane = 0x80000000
    # piece 0 -> grain 1, grain 2 -> piece 3 (force on the piece), grain 1 -> grain 2, a plane -> grain 2
    f.contact_first = np.array([0, 2, 1, plane], np.uint32)
    f.contact_second = np.array([1, 3, 2, 2], np.uint32)
    f.contact_points = np.array([[0.05, 0, 0], [0, 0, -0.05], [0.01, 0, 0], [0, 0, -0.06]], np.float32)
    f.contact_forces = np.array([[0, 0, 2.0], [-3.0, 0, 0], [0, 0, 7.0], [5.0, 0, 0]], np.float32)
    # About y: r x F for the first, (0,0,-0.05) x (+3,0,0) on the grain for the second.
    expected = np.cross([0.05, 0, 0], [0, 0, 2.0])[1] + np.cross([0, 0, -0.05], [3.0, 0, 0])[1]
    assert drum_angle.drum_torque(f, 1) == pytest.approx(expected, rel=1e-6)
    assert expected != 0
