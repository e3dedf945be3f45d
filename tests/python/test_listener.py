"""Forces from outside the engine (issue 53): a Python step listener writes
the applied forces through a NumPy view before the forces of every step.
A linear drag brings a falling grain to its terminal velocity m g / beta;
a bed under drag gives the same bits on 1 and 2 threads and across a stop
and resume; the drag's work is in the energy balance and energy.csv; bad
listeners and a listener's exception are reported."""
import shutil

import numpy as np
import pytest

import gjkdem


def lone_grain(gravity=(0.0, 0.0, -9.81)):
    s = gjkdem.Settings()
    s.gravity = list(gravity)
    b = gjkdem.WorldBuilder(s)
    b.add_material("m", density=2000, youngs_modulus=1e7)
    b.add_body(gjkdem.Shape("box", half_extents=[0.01, 0.01, 0.01]), "m", position=[0, 0, 1])
    return b.build()


def drag(beta):
    def listener(world, state):
        world.applied_forces[:] = -beta * world.velocities
    return listener


def test_a_drag_listener_gives_the_terminal_velocity():
    w = lone_grain()
    m = w.masses()[0]
    beta = m / 0.01  # relaxes in 10 ms: 0.3 s is 30 of them
    calls = []

    def listener(world, state):
        calls.append(state.step)
        drag(beta)(world, state)

    assert w.run(0.3, dt=1e-4, listener=listener) == "completed"
    terminal = m * 9.81 / beta
    assert w.velocities[0, 2] == pytest.approx(-terminal, rel=1e-6)
    assert len(calls) == 3001 and calls[:3] == [0, 0, 1]  # step 0's forces, then before every step's
    e = w.energies()
    assert e["applied_work"] < 0
    assert e["applied_work"] == pytest.approx(w.applied_work.sum())
    assert w.applied_forces[0, 2] == pytest.approx(m * 9.81, rel=1e-6)  # drag holds gravity


def test_an_applied_force_view_is_writable_and_pushes_the_body():
    w = lone_grain(gravity=(0, 0, 0))
    f = w.applied_forces
    assert f.shape == (1, 3) and f.flags.writeable and not f.flags.owndata
    m = w.masses()[0]
    f[0] = [2 * m, 0, 0]  # 2 m/s^2 from the next force evaluation on
    assert w.run(0.5, dt=1e-4) == "completed"
    assert w.velocities[0, 0] == pytest.approx(1.0, rel=1e-12)
    assert w.positions[0, 0] == pytest.approx(0.25, rel=1e-9)
    assert w.applied_work[0] == pytest.approx(0.5 * m * 1.0, rel=1e-12)
    with pytest.raises(ValueError, match="read-only"):
        w.applied_work[0] = 1.0


def bed(threads):
    s = gjkdem.Settings()
    s.model = "hertz"
    s.threads = threads
    b = gjkdem.WorldBuilder(s)
    b.add_material("glass", density=2500, youngs_modulus=1e7, restitution=0.5, friction=0.4)
    b.add_plane([0, 0, 0], [0, 0, 1], "glass")
    b.fill_region(gjkdem.Shape("sphere", radius=0.01), 40, [-0.05, -0.05, 0.0], [0.05, 0.05, 0.2], "glass", seed=4)
    return b.build()


def test_drag_gives_the_same_bits_on_one_and_two_threads():
    ends = []
    for threads in (1, 2):
        w = bed(threads)
        assert w.run(0.1, listener=drag(0.02), listener_every=2) == "completed"
        ends.append((w.positions.copy(), w.velocities.copy(), w.applied_forces.copy(), w.energies()))
    for a, b in zip(ends[0][:3], ends[1][:3]):
        assert np.array_equal(a, b)
    assert ends[0][3] == ends[1][3]


SAME_BYTES = ["trace.csv", "energy.csv", "view/index.csv"]


def test_drag_from_python_resumes_to_the_same_bytes(repo, tmp_path):
    src = repo / "tests" / "data" / "scenes"
    for name in ("small_pour.toml", "chute.obj"):
        shutil.copy(src / name, tmp_path / name)
    scene = str(tmp_path / "small_pour.toml")
    whole, parts = tmp_path / "whole", tmp_path / "parts"
    assert gjkdem.SceneRun(scene, out=str(whole), threads=1).run(listener=drag(0.01), listener_every=3) == "completed"
    assert gjkdem.SceneRun(scene, out=str(parts), threads=2).run(listener=drag(0.01), listener_every=3,
                                                                 stop_after=250) == "stopped"
    assert gjkdem.SceneRun.resume(str(parts), threads=1).run(listener=drag(0.01), listener_every=3) == "completed"
    for name in SAME_BYTES:
        assert (parts / name).read_bytes() == (whole / name).read_bytes(), name
    energy = (whole / "energy.csv").read_text().splitlines()
    assert energy[0].endswith(",applied_work")
    assert float(energy[-1].split(",")[-1]) < 0  # drag took energy out
    plain = tmp_path / "plain"
    assert gjkdem.SceneRun(scene, out=str(plain), threads=1).run() == "completed"
    assert (plain / "energy.csv").read_text().splitlines()[0].endswith(",inflow_energy")  # no loads, no column
    assert (plain / "trace.csv").read_bytes() != (whole / "trace.csv").read_bytes()  # the drag acted


def test_a_run_resumed_with_a_listener_gains_the_applied_work_column(repo, tmp_path):
    """A run stopped without applied loads and resumed with a drag: energy.csv
    gains the applied_work column, 0 on the rows before (no load did work),
    the drag's work after; the run stops and resumes again from there."""
    src = repo / "tests" / "data" / "scenes"
    for name in ("small_pour.toml", "chute.obj"):
        shutil.copy(src / name, tmp_path / name)
    scene, out = str(tmp_path / "small_pour.toml"), tmp_path / "out"
    assert gjkdem.SceneRun(scene, out=str(out), threads=1).run(stop_after=200) == "stopped"
    before = (out / "energy.csv").read_text().splitlines()
    assert not before[0].endswith(",applied_work")
    assert gjkdem.SceneRun.resume(str(out), threads=1).run(listener=drag(0.01), stop_after=400) == "stopped"
    assert gjkdem.SceneRun.resume(str(out), threads=1).run(listener=drag(0.01)) == "completed"
    rows = [line.split(",") for line in (out / "energy.csv").read_text().splitlines()]
    assert rows[0] == before[0].split(",") + ["applied_work"]
    assert all(len(r) == len(rows[0]) for r in rows)
    assert [",".join(r[:-1]) for r in rows[1:len(before)]] == before[1:]
    assert all(r[-1] == "0" for r in rows[1:len(before)])
    assert float(rows[-1][-1]) < 0  # the drag took energy out
    times = [float(r[0]) for r in rows[1:]]
    assert times == sorted(times) and len(set(times)) == len(times)


def test_a_log_that_gained_the_column_is_checkpointed_at_once(repo, tmp_path):
    """The column's rewrite is checkpointed when it happens: a run that fails
    before its next checkpoint resumes with energy.csv whole, every row as
    wide as the header."""
    src = repo / "tests" / "data" / "scenes"
    for name in ("small_pour.toml", "chute.obj"):
        shutil.copy(src / name, tmp_path / name)
    scene, out = str(tmp_path / "small_pour.toml"), tmp_path / "out"
    assert gjkdem.SceneRun(scene, out=str(out), threads=1).run(stop_after=200) == "stopped"

    def fail(world, state):
        raise RuntimeError("an observer fails")

    with pytest.raises(Exception, match="an observer fails"):
        gjkdem.SceneRun.resume(str(out), threads=1).run(listener=drag(0.01), observer=fail)
    assert gjkdem.SceneRun.resume(str(out), threads=1).run() == "completed"
    rows = [line.split(",") for line in (out / "energy.csv").read_text().splitlines()]
    assert rows[0][-1] == "applied_work" and all(len(r) == len(rows[0]) for r in rows)
    # The same for a run stopped and run again from Python without a resume.
    again = tmp_path / "again"
    r = gjkdem.SceneRun(scene, out=str(again), threads=1)
    assert r.run(stop_after=200) == "stopped"
    with pytest.raises(Exception, match="an observer fails"):
        r.run(listener=drag(0.01), observer=fail)
    del r  # lets go of the folder's lock
    assert gjkdem.SceneRun.resume(str(again), threads=1).run() == "completed"
    rows = [line.split(",") for line in (again / "energy.csv").read_text().splitlines()]
    assert rows[0][-1] == "applied_work" and all(len(r) == len(rows[0]) for r in rows)


def test_bad_listeners_are_refused_and_a_listeners_exception_is_raised():
    w = lone_grain()
    with pytest.raises(TypeError, match="listener"):
        w.run(1e-3, dt=1e-4, listener=3)
    with pytest.raises(ValueError, match="listener_every"):
        w.run(1e-3, dt=1e-4, listener=drag(1.0), listener_every=0)

    def broken(world, state):
        if state.step == 4:
            raise KeyError("no fluid cell here")

    with pytest.raises(KeyError, match="no fluid cell"):
        w.run(1e-3, dt=1e-4, listener=broken)
    assert w.time == pytest.approx(5e-4)  # failed mid-step, before the fifth step's forces
