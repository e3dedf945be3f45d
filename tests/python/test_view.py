"""gjkdem.read_view reads what a run wrote to view/ (docs/view-format.md):
every frame holds, to single precision, what the world held at that output
(seen by a Python observer through the bindings), and damaged files are
refused. gjkdem.analyze of the frames gives what World.measure gave live."""
import csv
import shutil

import numpy as np
import pytest

import gjkdem


REGION = ((-0.1, -0.1, -0.1), (0.1, 0.1, 0.05))  # the lower part of small_pour's box


@pytest.fixture
def run_dir(repo, tmp_path):
    src = repo / "tests" / "data" / "scenes"
    for name in ("small_pour.toml", "chute.obj"):
        shutil.copy(src / name, tmp_path / name)
    seen = []

    def observe(world, state):
        c = world.contacts()
        measures = world.measure(REGION[0], REGION[1])
        seen.append(dict(time=world.time, step=state.step, positions=world.positions.copy(),
                         orientations=world.orientations.copy(), velocities=world.velocities.copy(),
                         ids=world.ids.copy(), fixed=world.fixed.copy(),
                         contact_ids=c["ids"], contact_forces=c["forces"], contact_points=c["points"],
                         measures=measures))

    out = tmp_path / "out"
    assert gjkdem.SceneRun(str(tmp_path / "small_pour.toml"), out=str(out), threads=1).run(observer=observe) == "completed"
    return out, seen


def test_every_frame_holds_what_the_world_held(run_dir):
    out, seen = run_dir
    run = gjkdem.read_view(out)
    assert len(run) == len(seen) == 7
    assert list(run.index["step"]) == [s["step"] for s in seen]
    touching = 0
    for k, s in enumerate(seen):
        f = run.frame(k)
        assert f.time == s["time"] and f.step == s["step"]
        np.testing.assert_allclose(f.positions, s["positions"], atol=1e-7)
        np.testing.assert_allclose(f.orientations, s["orientations"], atol=1e-7)
        np.testing.assert_allclose(f.velocities, s["velocities"], rtol=1e-6, atol=1e-7)
        assert np.array_equal(f.ids, s["ids"])
        assert np.array_equal(f.flags & gjkdem.view.FIXED, s["fixed"])
        assert np.array_equal(f.fixed, s["fixed"] != 0) and not f.driven.any()  # the flags, readable
        # Contacts: the same pairs (by id; a plane is its wall id) and forces.
        ids = f.ids.astype(np.uint64)
        planes = run.plane_ids.astype(np.uint64)
        first = np.where(f.contact_first >= gjkdem.view.PLANE_SIDE,
                         planes[np.minimum(f.contact_first - gjkdem.view.PLANE_SIDE, len(planes) - 1)] if len(planes) else 0,
                         ids[np.minimum(f.contact_first, len(ids) - 1)])
        pairs = np.stack([first, ids[f.contact_second]], axis=1)
        assert np.array_equal(pairs, s["contact_ids"].astype(np.uint64) & 0xFFFFFFFF)
        np.testing.assert_allclose(f.contact_forces, s["contact_forces"], rtol=1e-6, atol=1e-9)
        np.testing.assert_allclose(f.contact_points, s["contact_points"], atol=1e-7)
        touching += len(f.contact_second)
    assert touching > 0, "the pour touches the ramp and the floor"
    # The surfaces: one per template, triangles naming their own vertices.
    assert len(run.templates) == int(max(run.frame(0).templates)) + 1
    for vertices, triangles in run.templates:
        assert vertices.shape[1] == 3 and triangles.shape[1] == 3 and triangles.max() < len(vertices)
    # Views of the file's bytes: read-only.
    with pytest.raises(ValueError):
        run.frame(0).positions[0, 0] = 1


def test_damaged_view_files_are_refused(run_dir, tmp_path):
    out, _ = run_dir
    frame = out / "view" / "frame_000003.bin"
    data = frame.read_bytes()
    for damaged, why in [(data[:-3], "cut short"), (data + b"\0", "past its end"), (b"GJKSHAPE" + data[8:], "wrong magic"),
                         (data[:8] + b"\x05" + data[9:], "version 5")]:
        with pytest.raises(gjkdem.ViewFormatError, match=why):
            gjkdem.view.Frame(damaged)
    (out / "view" / "shapes.bin").write_bytes((out / "view" / "shapes.bin").read_bytes()[:20])
    with pytest.raises(gjkdem.ViewFormatError):
        gjkdem.read_view(out)
    with pytest.raises(FileNotFoundError, match="holds no shapes.bin"):
        gjkdem.read_view(tmp_path)


@pytest.mark.parametrize("row, why", [("3,abc,1,2,3", "line 3"), ("3,0.1,1,2", "line 3"), ("3,0.1,1,2,3,4", "line 3"),
                                      ("3,nan,1,2,3", "line 3"), ("3,0.1,-1,2,3", "line 3"), ("(1,2),0,0,0,0", "line 3")])
def test_a_damaged_index_names_its_file_and_line(run_dir, row, why):
    out, _ = run_dir
    index = out / "view" / "index.csv"
    lines = index.read_text().splitlines()
    index.write_text("\n".join(lines[:2] + [row] + lines[3:]) + "\n")
    with pytest.raises(gjkdem.ViewFormatError, match=why) as e:
        gjkdem.read_view(out)
    assert "index.csv" in str(e.value)


def test_a_frame_naming_a_template_the_shapes_lack_is_refused(run_dir):
    out, _ = run_dir
    view = gjkdem.read_view(out)
    frame = out / "view" / "frame_000003.bin"
    data = bytearray(frame.read_bytes())
    n = len(view.frame(3))
    templates_at = 40 + 4 * 13 * n  # after magic, version, counts, time, step and 13 floats a body
    data[templates_at:templates_at + 4] = (10**6).to_bytes(4, "little")
    frame.write_bytes(bytes(data))
    with pytest.raises(gjkdem.ViewFormatError, match="shape template"):
        view.frame(3)


def test_the_analysis_of_the_frames_is_the_live_worlds(run_dir):
    out, seen = run_dir
    summary = gjkdem.analyze(str(out), region=REGION)
    assert summary["frames"] == 7
    rows = list(csv.DictReader(open(out / "analysis" / "measures.csv")))
    assert len(rows) == len(seen)
    pressed = 0
    for row, s in zip(rows, seen):
        live = s["measures"]
        assert int(row["grains"]) == live["grains"] and int(row["contacts"]) == live["contacts"]
        assert float(row["coordination"]) == pytest.approx(live["coordination"], rel=1e-8)
        # The frames hold single precision: poses and forces to about 1e-7.
        assert float(row["solid_fraction"]) == pytest.approx(live["solid_fraction"], rel=1e-5, abs=1e-9)
        assert float(row["pressure"]) == pytest.approx(live["pressure"], rel=1e-4, abs=1e-9)
        assert float(row["stress_zz"]) == pytest.approx(live["stress"][2, 2], rel=1e-4, abs=1e-9)
        pressed += live["pressure"] > 0
    assert pressed > 0
    world = gjkdem.load_scene(str(out.parent / "small_pour.toml")).world
    with pytest.raises(ValueError, match="lo < hi"):
        world.measure((0, 0, 0), (1, 0, 1))


def test_a_run_folder_loads_at_its_last_checkpoint(run_dir):
    out, seen = run_dir
    scene = gjkdem.load_run(str(out))
    w = scene.world
    # small_pour checkpoints every 2 outputs and at its end: the last is its last frame.
    k = [s["time"] for s in seen].index(w.time)
    assert k == 6
    f = gjkdem.read_view(out).frame(k)
    np.testing.assert_allclose(w.positions, f.positions, atol=1e-7)
    assert w.contact_count == len(f.contact_second)
    # A checkpoint of a run folder is of its scene: a world built otherwise is refused.
    other = gjkdem.load_scene(str(out.parent / "small_pour.toml")).world
    with pytest.raises(ValueError, match="scene"):
        other.load_checkpoint(str(out / "checkpoint.bin"))
    # ... unless it starts a new run from that state (its clock at 0).
    assert other.load_checkpoint(str(out / "checkpoint.bin"), restart=True) == pytest.approx(1e-4)
    assert other.time == 0
    np.testing.assert_array_equal(other.positions, w.positions)
    with pytest.raises(ValueError, match="run.json is missing"):
        gjkdem.load_run(str(out.parent))  # not a run folder


def test_a_bonded_drop_s_frames_hold_its_bonds(repo, tmp_path):
    """The frames of a bonded assembly's run hold its bonds (version 3): all
    intact at the start, as many broken at the end as run.json counts, their
    faces between their two pieces."""
    shutil.copy(repo / "tests" / "data" / "scenes" / "bonded_drop.toml", tmp_path / "bonded_drop.toml")
    out = tmp_path / "out"
    assert gjkdem.SceneRun(str(tmp_path / "bonded_drop.toml"), out=str(out), threads=1).run() == "completed"
    run = gjkdem.read_view(out)
    first, last = run.frame(0), run.frame(-1)
    assert len(first.bond_first) == 38 and first.bond_intact.all()
    import json
    info = json.loads((out / "run.json").read_text())
    assert (~last.bond_intact).sum() == info["bonds_broken"] > 0
    for f in (first, last):
        a, b = f.positions[f.bond_first], f.positions[f.bond_second]
        # The face centre lies nearer each piece's centre than the pieces' centres lie apart (0.02 m box).
        assert np.all(np.linalg.norm(f.bond_points - a, axis=1) < np.linalg.norm(b - a, axis=1) + 0.02)


def test_a_scenes_applied_loads_move_its_ball_and_travel_as_channels(repo, tmp_path):
    """A scene's constant applied_force and applied_torque (pulled_ball.toml)
    accelerate the ball as F/m and T/I, their work is energy.csv's
    applied_work, and the frames' channel block holds them by name."""
    shutil.copy(repo / "tests" / "data" / "scenes" / "pulled_ball.toml", tmp_path / "pulled_ball.toml")
    out = tmp_path / "out"
    assert gjkdem.SceneRun(str(tmp_path / "pulled_ball.toml"), out=str(out), threads=1).run() == "completed"
    force, torque, radius = 0.02, 1.0e-6, 0.01
    mass = 7800.0 * 4.0 / 3.0 * np.pi * radius**3
    inertia = 0.4 * mass * radius**2
    with open(out / "trace.csv") as f:
        rows = [r for r in csv.DictReader(f) if r["name"] == "pulled"]
    assert len(rows) == 6
    for r in rows:
        t = float(r["time"])
        assert float(r["x"]) == pytest.approx(force * t**2 / (2 * mass), rel=1e-9, abs=1e-15)
        assert float(r["wz"]) == pytest.approx(torque * t / inertia, rel=1e-9, abs=1e-15)
    with open(out / "energy.csv") as f:
        last = list(csv.DictReader(f))[-1]
    t = float(last["time"])
    work = force * force * t**2 / (2 * mass) + torque * torque * t**2 / (2 * inertia)
    assert float(last["applied_work"]) == pytest.approx(work, rel=1e-9)
    run = gjkdem.read_view(out)
    for k in range(len(run)):
        frame = run.frame(k)
        assert list(frame.channels) == ["applied_force", "applied_torque"]
        assert frame.channel_units == {"applied_force": "N", "applied_torque": "N m"}
        np.testing.assert_array_equal(frame.channels["applied_force"], np.float32([[force, 0, 0], [0, 0, 0]]))
        np.testing.assert_array_equal(frame.channels["applied_torque"], np.float32([[0, 0, torque], [0, 0, 0]]))
    # The exported state keeps the loads: they are state.
    exported = tmp_path / "again.toml"
    gjkdem.export_scene(str(out), path=str(exported))
    again = gjkdem.load_scene(str(exported)).world
    np.testing.assert_array_equal(again.applied_forces, [[force, 0, 0], [0, 0, 0]])
    np.testing.assert_array_equal(again.applied_torques, [[0, 0, torque], [0, 0, 0]])


def test_a_run_without_loads_has_no_channels(run_dir):
    out, _ = run_dir
    assert gjkdem.read_view(out).frame(-1).channels == {}
