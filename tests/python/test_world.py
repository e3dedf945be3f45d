"""Worlds from Python: the builder, views that alias the engine's memory,
setters, runs with observers, contacts, energies, checkpoints, and the
errors of bad input."""
import math
import pathlib

import numpy as np
import pytest

import gjkdem


def small_bed(model="hertz", count=40, seed=1):
    s = gjkdem.Settings()
    s.model = model
    b = gjkdem.WorldBuilder(s)
    b.add_material("glass", density=2500, youngs_modulus=1e7, restitution=0.5, friction=0.4)
    b.add_plane([0, 0, 0], [0, 0, 1], "glass")
    b.fill_region(gjkdem.Shape("sphere", radius=0.01), count, [-0.05, -0.05, 0.0], [0.05, 0.05, 0.2], "glass",
                  seed=seed)
    return b.build()


def test_views_alias_the_bodies_and_setters_write_through():
    w = small_bed()
    p = w.positions
    assert p.shape == (40, 3) and not p.flags.writeable and not p.flags.owndata
    w.set_positions(np.array([[0.01, 0.02, 0.5]]), indices=[3])
    assert list(p[3]) == [0.01, 0.02, 0.5]  # the old view sees the new value: no copy
    q = np.array([[math.cos(0.3), 0, 0, math.sin(0.3)]])
    w.set_orientations(q, indices=[3])
    assert np.allclose(w.orientations[3], q[0])
    v = w.velocities
    assert v.flags.writeable
    v[5] = [0.0, 0.0, -2.0]
    assert list(w.velocities[5]) == [0.0, 0.0, -2.0]
    with pytest.raises(ValueError, match="read-only"):
        p[0, 0] = 1.0
    ids = w.ids
    assert ids.dtype == np.uint64 and list(ids) == list(range(40))


def test_written_velocities_move_the_bodies():
    s = gjkdem.Settings()
    s.gravity = [0, 0, 0]
    b = gjkdem.WorldBuilder(s)
    b.add_material("m", 1000, 1e6)
    b.add_body(gjkdem.Shape("box", half_extents=[0.1, 0.1, 0.1]), "m", position=[0, 0, 0])
    w = b.build()
    w.velocities[0] = [1.0, 0.0, 0.0]
    for _ in range(10):
        w.step(0.01)
    assert w.positions[0, 0] == pytest.approx(0.1)
    assert w.time == pytest.approx(0.1)


def test_a_run_calls_the_observer_at_its_cadence_and_stops_when_told():
    w = small_bed()
    seen = []

    def observer(world, state):
        seen.append((state.step, world.time))
        return state.outputs < 3

    status = w.run(0.2, dt=1e-4, output_every=0.01, observer=observer)
    assert status == "stopped"
    assert [s for s, _ in seen] == [0, 100, 200]
    status = w.run(0.05, dt=1e-4, output_every=0.01)
    assert status == "completed" and w.time == pytest.approx(0.02 + 0.05)


def test_an_observers_exception_comes_back_and_the_run_stops():
    w = small_bed()

    def observer(world, state):
        if state.step > 0:
            raise KeyError("mine")

    with pytest.raises(KeyError, match="mine"):
        w.run(0.1, dt=1e-4, output_every=0.01, observer=observer)
    assert w.time == pytest.approx(0.01)


def test_a_settled_bed_has_contacts_and_its_energy_balances():
    w = small_bed(count=30)
    w.run(0.4)
    c = w.contacts()
    n = w.contact_count
    assert n > 0 and c["ids"].shape == (n, 2) and c["forces"].shape == (n, 3)
    # At rest, the contact forces carry the weight: their vertical sum on the floor's contacts.
    floor = c["ids"][:, 0] >= 2**62
    weight = w.masses().sum() * 9.81
    assert c["forces"][floor, 2].sum() == pytest.approx(weight, rel=1e-2)
    e = w.energies()
    assert e["kinetic"] < 1e-6 * abs(e["potential"]) + 1e-12
    assert np.all(np.linalg.norm(c["normals"], axis=1) == pytest.approx(1.0))


def test_a_checkpoint_brings_the_world_back_bit_for_bit(tmp_path):
    w = small_bed()
    w.run(0.05, dt=1e-4)
    path = tmp_path / "bed.ckpt"
    w.save_checkpoint(str(path), dt=1e-4)
    before = w.positions.copy()
    w.run(0.02, dt=1e-4)
    after_first = w.positions.copy()
    assert w.load_checkpoint(str(path)) == 1e-4
    assert np.array_equal(w.positions, before)
    w.run(0.02, dt=1e-4)
    assert np.array_equal(w.positions, after_first)
    other = small_bed(count=10)
    with pytest.raises(gjkdem.CheckpointError):
        other.load_checkpoint(str(path))


def test_an_unsupported_pair_or_a_blown_run_raises_run_error():
    b = gjkdem.WorldBuilder()
    b.add_material("m", 2500, 1e7)
    b.add_body(gjkdem.Shape("box", half_extents=[0.01] * 3), "m", velocity=[0, 0, -1], position=[0, 0, 0.0105])
    b.add_plane([0, 0, 0], [0, 0, 1], "m")
    w = b.build()
    with pytest.raises(gjkdem.RunError, match="time step"):
        w.run(0.01, dt=1e-2 / 3)  # far beyond the stable step: the guard stops it
    assert issubclass(gjkdem.RunError, RuntimeError)


@pytest.mark.parametrize(
    "build, message",
    [
        (lambda b: b.add_material("bad", -1, 1e7), "material 'bad': density must be > 0"),
        (lambda b: b.add_material("m", 1, 1e7), "material 'm': name is defined twice"),
        (lambda b: b.add_body(gjkdem.Shape("sphere", radius=1.0), "nope"), "material: no material is named 'nope'"),
        (lambda b: b.add_body(gjkdem.Shape("sphere", radius=1.0), 7), "body 0: material 7 was never added"),
        (lambda b: b.add_body(gjkdem.Shape("sphere", radius=1.0), "m", rotation=[1, 1, 0, 0]),
         "rotation: quaternion [w, x, y, z] must be unit"),
        (lambda b: b.add_body(gjkdem.Shape("sphere", radius=1.0), "m", position=[0, float("nan"), 0]),
         "position: NaN or infinite number"),
        (lambda b: b.add_body(gjkdem.Shape("sphere", radius=1.0), "m", velocity=[0, 0]),
         "velocity: expected 3 numbers, got an array of shape (2,)"),
        (lambda b: b.add_plane([0, 0, 0], [0, 0, 0], "m"), "plane"),
    ],
)
def test_bad_builder_input_raises_value_error(build, message):
    b = gjkdem.WorldBuilder()
    b.add_material("m", 2500, 1e7)
    with pytest.raises(ValueError) as e:
        build(b)
    assert message in str(e.value)


def test_overlapping_bodies_are_refused_naming_them():
    b = gjkdem.WorldBuilder()
    b.add_material("m", 2500, 1e7)
    s = gjkdem.Shape("box", half_extents=[0.01] * 3)
    b.add_body(s, "m", label="left")
    b.add_body(s, "m", position=[0.015, 0, 0], label="right")
    with pytest.raises(gjkdem.BuildError, match="left overlaps right"):
        b.build()


def test_bad_setter_input_raises_value_error():
    w = small_bed(count=5)
    with pytest.raises(ValueError, match="expected one row per body"):
        w.set_positions(np.zeros((3, 3)))
    with pytest.raises(ValueError, match="body index 9 out of range"):
        w.set_positions(np.zeros((1, 3)), indices=[9])
    with pytest.raises(ValueError, match="not finite"):
        w.set_positions(np.full((1, 3), np.inf), indices=[0])
    with pytest.raises(ValueError, match=r"row 0 is outside the supported range \[-1e100, 1e100\]"):
        w.set_positions(np.array([[0, 0, 1e101]]), indices=[0])  # as add_body refuses it
    with pytest.raises(ValueError, match="must be unit"):
        w.set_orientations(np.array([[2.0, 0, 0, 0]]), indices=[0])
    with pytest.raises(ValueError, match=r"shape \(N, 4\)"):
        w.set_orientations(np.zeros((1, 3)), indices=[0])
    with pytest.raises(ValueError, match="dt: must be finite and > 0"):
        w.step(float("nan"))


def test_ctrl_c_stops_a_run_with_keyboard_interrupt():
    import signal

    def interrupt(signum, frame):
        raise KeyboardInterrupt

    w = small_bed(count=20)
    previous = signal.signal(signal.SIGALRM, interrupt)
    signal.setitimer(signal.ITIMER_REAL, 0.3)
    try:
        with pytest.raises(KeyboardInterrupt):
            w.run(1000.0, dt=1e-4)  # hours of steps: only the interrupt ends it
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)
    assert 0 < w.time < 1000.0


def test_a_run_can_write_a_run_folder_as_the_program_does(tmp_path):
    import json

    w = small_bed(count=10)
    out = tmp_path / "bed"
    assert w.run(0.02, dt=1e-4, output_every=0.005, out=str(out), checkpoint_every=2, frames=True) == "completed"
    info = json.loads((out / "run.json").read_text())
    assert info["status"] == "completed" and info["bodies"] == 10 and info["steps"] == 200
    energy = (out / "energy.csv").read_text().splitlines()
    assert len(energy) == 1 + 5 and energy[0].startswith("time")
    assert len(list((out / "frames").glob("frame_*.vtk"))) == 5
    assert (out / "checkpoint.bin").stat().st_size > 0
    with pytest.raises(gjkdem.RunFolderError, match="overwrite"):
        w.run(0.01, dt=1e-4, out=str(out))
    # Lean by default: the view frames (viewer, analyze), no VTK.
    assert w.run(0.01, dt=1e-4, out=str(out), overwrite=True) == "completed"
    assert not list((out / "frames").glob("frame_*.vtk")) and len(list((out / "view").glob("frame_*.bin"))) == 2


def test_progress_is_the_programs_line_on_stderr(capsys):
    w = small_bed(count=10)
    assert w.run(0.01, dt=1e-4, progress=True) == "completed"
    err = capsys.readouterr().err.strip().splitlines()
    assert err and err[-1].startswith("gjkdem: t = 0.0100 / 0.01 s  100.0%") and "steps/s  ETA 0m00s" in err[-1]


def test_a_ball_rests_on_a_mesh_wall_as_on_a_plane():
    def resting_height(add_floor):
        s = gjkdem.Settings()
        s.model = "hertz"
        b = gjkdem.WorldBuilder(s)
        b.add_material("m", 2500, 1e7)
        add_floor(b)
        b.add_body(gjkdem.Shape("sphere", radius=0.01), "m", position=[0.001, 0.002, 0.0101])
        w = b.build()
        w.run(0.3)
        return w.positions[-1, 2]

    square = np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], dtype=float)
    # Under Hertz a triangle is rounded by half the thickness: its top lies 1 mm above its vertices.
    sunk = square - [0, 0, 0.001]
    on_mesh = resting_height(lambda b: b.add_mesh_walls(sunk, [[0, 1, 2], [0, 2, 3]], 0.002, "m"))
    on_plane = resting_height(lambda b: b.add_plane([0, 0, 0], [0, 0, 1], "m"))
    assert on_mesh == pytest.approx(on_plane, abs=1e-9)
    b = gjkdem.WorldBuilder()
    b.add_material("m", 2500, 1e7)
    # The indices are read as gjkdem.Surface reads them, and checked by the
    # library's one rule: out of range, a fraction (not truncated), a
    # vertex named twice.
    for triangles, why in [([[0, 1, 2], [0, 2, 4]], r"triangles\[1\]: must hold indices of vertices"),
                           ([[0, 1, 2], [0, 2, 2.5]], r"triangles\[1\]: must hold indices of vertices"),
                           ([[0, 1, 2], [0, 0, 0]], r"mesh: triangle 1 repeats a vertex \(0, 0, 0\)")]:
        with pytest.raises(ValueError, match=why):
            b.add_mesh_walls(square, triangles, 0.002, "m")


def test_a_belt_carries_a_grain_and_its_work_is_counted():
    s = gjkdem.Settings()
    s.model = "linear"
    b = gjkdem.WorldBuilder(s)
    b.add_material("rubber", density=1200, youngs_modulus=1e7, friction=0.8, rolling_friction=0.1)
    belt = b.add_motion(velocity=[0.3, 0, 0])
    slab = b.add_body(gjkdem.Shape("box", half_extents=[0.5, 0.1, 0.01]), "rubber", position=[0, 0, -0.01],
                      fixed=True, motion=belt)
    b.add_body(gjkdem.Shape("box", half_extents=[0.01, 0.01, 0.01]), "rubber", position=[0, 0, 0.01])
    w = b.build()
    assert list(w.motions) == [belt, 0] and w.motions.dtype == np.uint16
    w.run(0.2)
    assert w.velocities[1][0] == pytest.approx(0.3, rel=0.01)
    assert w.positions[slab][0] == pytest.approx(0.3 * w.time, abs=1e-12)
    # The belt did the work of the grain's kinetic energy and of the friction while it slipped.
    e = w.energies()
    kinetic = 0.5 * w.masses()[1] * 0.3 ** 2
    assert e["wall_work"] >= e["kinetic"] > 0.99 * kinetic
    bad = gjkdem.WorldBuilder(s)
    bad.add_material("rubber", density=1200, youngs_modulus=1e7)
    with pytest.raises(ValueError, match="times must increase"):
        bad.add_motion(table=[[0, 0, 0, 0], [0, 1, 0, 0]])
    with pytest.raises(ValueError, match="for fixed bodies"):
        bad.add_body(gjkdem.Shape("sphere", radius=0.01), "rubber", motion=bad.add_motion(velocity=[1, 0, 0]))


def test_an_inflow_adds_bodies_and_old_views_stay_valid():
    s = gjkdem.Settings()
    s.model = "hertz"
    b = gjkdem.WorldBuilder(s)
    b.add_material("glass", density=2500, youngs_modulus=1e7)
    b.add_body(gjkdem.Shape("sphere", radius=0.01), "glass", position=[0, 0, 1])
    b.add_inflow([gjkdem.Shape("sphere", radius=0.004), gjkdem.Shape("sphere", radius=0.006)], [0, 0, 0.5],
                 [0.1, 0.1, 0.5], "glass", rate=200, stop=0.5, weights=[3, 1], velocity=[0, 0, -1])
    w = b.build()
    before = w.positions  # a view of the one body there now
    assert before.shape == (1, 3)
    w.run(0.3)
    assert w.body_count == pytest.approx(1 + 61, abs=1)  # bodies 0..60 due in [0, 0.3]
    assert before[0][2] == w.positions[0][2] < 1  # the old view still aliases body 0: it fell
    assert w.positions.shape == (w.body_count, 3)
    e = w.energies()
    assert e["inflow_energy"] > 0
    bad = gjkdem.WorldBuilder(s)
    bad.add_material("glass", density=2500, youngs_modulus=1e7)
    with pytest.raises(ValueError, match="give a count or a stop time"):
        bad.add_inflow(gjkdem.Shape("sphere", radius=0.004), [0, 0, 0], [1, 1, 1], "glass", rate=1)


def test_an_inflow_from_a_disc_places_its_bodies_on_it():
    s = gjkdem.Settings()
    s.gravity = [0, 0, 0]
    b = gjkdem.WorldBuilder(s)
    b.add_material("glass", density=2500, youngs_modulus=1e7)
    b.add_inflow(gjkdem.Shape("sphere", radius=0.002), material="glass", rate=1000, count=50,
                 cylinder={"base": [0.1, 0, 0.3], "axis": [0, 0, 1], "radius": 0.03, "height": 0})
    w = b.build()
    w.run(0.06, dt=1e-4)
    assert w.body_count == 50
    r = np.linalg.norm(w.positions[:, :2] - [0.1, 0], axis=1)
    assert r.max() <= 0.03 and np.all(w.positions[:, 2] == pytest.approx(0.3, abs=1e-12))
    with pytest.raises(ValueError, match="give the region once"):
        b.add_inflow(gjkdem.Shape("sphere", radius=0.002), [0, 0, 0], [1, 1, 1], "glass", rate=1, count=1,
                     sphere={"centre": [0, 0, 0], "radius": 1})


def test_a_compound_grain_from_python():
    foot = gjkdem.Shape("box", half_extents=[0.02, 0.005, 0.005], center=[0.02, 0, 0.005])
    leg = gjkdem.Shape("box", half_extents=[0.005, 0.005, 0.015], center=[0.005, 0, 0.025])
    ell = gjkdem.Shape.compound([foot, leg])
    assert ell.parts == 2 and ell.type == "compound"
    assert ell.volume == pytest.approx(7e-6, rel=1e-12)
    with pytest.raises(ValueError, match="queries take one convex shape"):
        gjkdem.intersect(ell, foot)
    s = gjkdem.Settings()
    s.model = "hertz"
    b = gjkdem.WorldBuilder(s)
    b.add_material("rock", density=2500, youngs_modulus=1e7)
    b.add_plane([0, 0, 0], [0, 0, 1], "rock")
    b.add_body(ell, "rock", position=[0, 0, 0.001])
    w = b.build()
    w.run(0.2)
    assert w.masses()[0] == pytest.approx(2500 * 7e-6, rel=1e-12)
    assert w.positions[0][2] == pytest.approx(ell.centroid[2], abs=1e-3)  # resting on its foot
    overlapping = gjkdem.Shape.compound([foot, gjkdem.Shape("box", half_extents=[0.005, 0.005, 0.015],
                                                            center=[0.005, 0, 0.02])])
    bad = gjkdem.WorldBuilder(s)
    bad.add_material("rock", density=2500, youngs_modulus=1e7)
    with pytest.raises(ValueError, match="parts 0 and 1 overlap"):
        bad.add_body(overlapping, "rock")


def test_a_periodic_cell_from_python():
    s = gjkdem.Settings()
    s.model = "hertz"
    s.gravity = [0, 0, 0]
    s.periodic = {"x": (0.0, 0.1)}
    assert s.periodic == {"x": (0.0, 0.1)}
    with pytest.raises(ValueError, match="keys are"):
        s.periodic = {"w": (0, 1)}
    b = gjkdem.WorldBuilder(s)
    b.add_material("glass", density=2500, youngs_modulus=1e7)
    b.add_body(gjkdem.Shape("sphere", radius=0.005), "glass", position=[0.09, 0, 0], velocity=[1, 0, 0])
    w = b.build()
    w.run(0.03, dt=1e-4)
    assert w.positions[0][0] == pytest.approx(0.02, abs=1e-9)  # left at x = 0.1, came back at 0


def test_a_deforming_cell_from_python():
    # A cell stretched along x at 0.5 1/s: its length follows the rate, and
    # world.cell reports it with the rate.
    s = gjkdem.Settings()
    s.model = "hertz"
    s.gravity = [0, 0, 0]
    s.periodic = {"x": (0.0, 0.1)}
    s.cell_control = {"strain_rate": {"x": 0.5}}
    assert s.cell_control == {"strain_rate": {"x": 0.5}}
    with pytest.raises(ValueError, match="components are"):
        s.cell_control = {"strain_rate": {"zx": 1.0}}
    b = gjkdem.WorldBuilder(s)
    b.add_material("glass", density=2500, youngs_modulus=1e7)
    b.add_body(gjkdem.Shape("sphere", radius=0.005), "glass", position=[0.05, 0, 0])
    w = b.build()
    for _ in range(100):
        w.step(1e-3)
    cell = w.cell
    assert cell["hi"][0] - cell["lo"][0] == pytest.approx(0.1 * (1 + 0.5e-3) ** 100, rel=1e-12)
    assert cell["strain_rate"]["x"] == 0.5
    assert cell["strain_rate"]["xz"] == 0.0
    assert w.velocities[0][0] == pytest.approx(0.0, abs=1e-12)  # at the centre the field is still


def test_bodies_given_one_shape_object_share_one_template():
    def pile(shape_for):
        b = gjkdem.WorldBuilder()
        b.add_material("rock", density=2600, youngs_modulus=1e7)
        b.add_plane([0, 0, 0], [0, 0, 1], "rock")
        for k in range(30):
            b.add_body(shape_for(k), "rock", position=[0.05 * (k % 6), 0.05 * (k // 6), 0.1])
        b.add_body(shape_for(99), "rock", position=[1, 1, 1], fixed=True)  # a fixed one: a wall template
        return b.build()

    cube = gjkdem.Shape("box", half_extents=[0.02, 0.02, 0.02])
    shared = pile(lambda k: cube)
    apart = pile(lambda k: gjkdem.Shape("box", half_extents=[0.02, 0.02, 0.02]))
    assert shared.template_count == 2
    assert apart.template_count == 31
    # The same world either way.
    for w in (shared, apart):
        w.run(duration=0.01, dt=1e-4)
    assert np.array_equal(shared.positions, apart.positions)


def test_a_folder_written_from_python_is_analyzed_with_its_world(tmp_path):
    w = small_bed()
    assert w.run(0.03, output_every=0.01, out=str(tmp_path / "run")) == "completed"
    summary = gjkdem.analyze(str(tmp_path / "run"), world=w)
    assert summary["frames"] == 5 and summary["largest_frame"] == 40
    rows = (tmp_path / "run" / "analysis" / "measures.csv").read_text().splitlines()
    assert len(rows) == 6 and rows[-1].split(",")[13] == "40"  # grains in the last frame
    with pytest.raises(gjkdem.SceneError, match=r"gjkdem.analyze\(folder, world=that World\)"):
        gjkdem.analyze(str(tmp_path / "run"))  # the folder keeps no scene
    s = gjkdem.Settings()
    b = gjkdem.WorldBuilder(s)
    b.add_material("m", 1000, 1e6)
    b.add_body(gjkdem.Shape("box", half_extents=[0.1, 0.1, 0.1]), "m", position=[0, 0, 0])
    with pytest.raises(ValueError, match="did not write"):
        gjkdem.analyze(str(tmp_path / "run"), world=b.build())


def test_named_bodies_are_traced_as_in_scenes(tmp_path):
    s = gjkdem.Settings()
    b = gjkdem.WorldBuilder(s)
    b.add_material("glass", density=2500, youngs_modulus=1e7)
    b.add_plane([0, 0, 0], [0, 0, 1], "glass")
    ball = gjkdem.Shape("sphere", radius=0.01)
    b.add_body(ball, "glass", position=[0, 0, 0.05], name="tracer")
    b.add_body(ball, "glass", position=[0.05, 0, 0.05])
    with pytest.raises(ValueError, match="two bodies are named 'tracer'"):
        b.add_body(ball, "glass", position=[0.1, 0, 0.05], name="tracer")
    with pytest.raises(ValueError, match="its name holds a comma"):
        b.add_body(ball, "glass", position=[0.1, 0, 0.05], name="a,b")
    w = b.build()
    assert w.names == {"tracer": 0}
    assert w.run(0.02, output_every=0.01, out=str(tmp_path / "run")) == "completed"
    rows = (tmp_path / "run" / "trace.csv").read_text().splitlines()
    assert rows[0].startswith("time,name,x,y,z") and len(rows) == 4
    assert all(r.split(",")[1] == "tracer" for r in rows[1:])
    assert float(rows[-1].split(",")[4]) < 0.05  # it fell
    scene = gjkdem.load_scene(str(pathlib.Path(__file__).parents[1] / "data" / "scenes" / "small_pour.toml"))
    assert list(scene.world.names) == ["tracer"]  # a scene's named body: the same notion (after the walls)


def test_balls_thrown_about_in_a_cylinder_stay_inside():
    s = gjkdem.Settings()
    s.model = "hertz"
    b = gjkdem.WorldBuilder(s)
    b.add_material("glass", density=2500, youngs_modulus=1e7, restitution=0.3, friction=0.4)
    b.add_cylinder_walls([0, 0, 0], [0, 0, 1], radius=0.03, height=0.1, material="glass")
    b.fill_region(gjkdem.Shape("sphere", radius=0.004), 40, [-0.02, -0.02, 0.01], [0.02, 0.02, 0.09], "glass",
                  seed=2)
    w = b.build()
    moving = w.fixed == 0
    w.velocities[moving] = [3.0, 2.0, 0.0]
    assert w.run(0.2) == "completed"
    p = w.positions[moving]
    assert np.hypot(p[:, 0], p[:, 1]).max() + 0.004 < 0.0302 and p[:, 2].min() - 0.004 > -2e-4
    b = gjkdem.WorldBuilder(s)  # build() emptied the first
    b.add_material("glass", density=2500, youngs_modulus=1e7)
    with pytest.raises(ValueError, match="segments must be 8 to 4096"):
        b.add_cylinder_walls([0, 0, 0], [0, 0, 1], radius=0.03, height=0.1, material="glass", segments=3)
    with pytest.raises(ValueError, match="non-zero axis"):
        b.add_cylinder_walls([0, 0, 0], [0, 0, 0], radius=0.03, height=0.1, material="glass")


def test_fill_region_takes_cylinders_and_spheres():
    s = gjkdem.Settings()
    b = gjkdem.WorldBuilder(s)
    b.add_material("glass", density=2500, youngs_modulus=1e7)
    ball = gjkdem.Shape("sphere", radius=0.004)
    in_cylinder = b.fill_region(ball, 100, material="glass",
                                cylinder={"base": [0, 0, 0], "axis": [0, 0, 1], "radius": 0.03, "height": 0.1})
    in_sphere = b.fill_region(ball, 40, material="glass", sphere={"centre": [0, 0, 0.5], "radius": 0.03})
    with pytest.raises(ValueError, match="give the region once"):
        b.fill_region(ball, 4, [0, 0, 1], [1, 1, 2], "glass", sphere={"centre": [0, 0, 0.5], "radius": 0.03})
    with pytest.raises(ValueError, match="needs 'height'"):
        b.fill_region(ball, 4, material="glass", cylinder={"radius": 0.03})
    w = b.build()
    p = w.positions
    c = p[in_cylinder]
    assert (np.hypot(c[:, 0], c[:, 1]) + 0.004 <= 0.03 + 1e-12).all() and c[:, 2].min() >= 0.004 - 1e-12
    assert (np.linalg.norm(p[in_sphere] - [0, 0, 0.5], axis=1) + 0.004 <= 0.03 + 1e-12).all()


def test_shapes_take_the_scenes_vocabulary(repo, tmp_path):
    cube = gjkdem.Shape("platonic", name="cube", size=0.02)
    assert cube.type == "platonic" and cube.volume > 0
    drawn = [gjkdem.Shape("random_polyhedron", vertices=12, size=[0.012, 0.018], seed=s).volume for s in (3, 3, 4)]
    assert drawn[0] == drawn[1] != drawn[2]  # one shape per seed
    ell = gjkdem.Shape("compound", parts=[{"type": "box", "half_extents": [0.01, 0.01, 0.01]},
                                          {"type": "box", "half_extents": [0.01, 0.01, 0.01], "center": [0.02, 0, 0]}])
    assert ell.parts == 2 and ell.volume == pytest.approx(1.6e-5)
    with pytest.warns(UserWarning, match="not convex"):
        hull = gjkdem.Shape("mesh", file=str(repo / "examples" / "scenes" / "rock.obj"))
    assert hull.volume > 0
    b = gjkdem.WorldBuilder(gjkdem.Settings())
    b.add_material("rock", density=2500, youngs_modulus=1e7)
    b.fill_region([cube, ell, hull], 30, [0, 0, 0], [0.3, 0.3, 0.3], "rock")  # all of them are body shapes
    assert b.build().template_count == 3
    for fields, words in [(dict(name="cubee", size=1.0), "unknown platonic solid"),
                          (dict(name="cube", size=-1.0), "size")]:
        with pytest.raises(ValueError, match=words):
            gjkdem.Shape("platonic", **fields)
    with pytest.raises(ValueError, match="between 4 and 10000"):
        gjkdem.Shape("random_polyhedron", vertices=2, size=0.01)
    with pytest.raises(ValueError, match="file not found"):
        gjkdem.Shape("mesh", file=str(tmp_path / "none.stl"))
    with pytest.raises(ValueError, match="gjkdem.Surface"):
        gjkdem.Shape("surface", file="rock.obj")


def test_grains_break_in_a_press_and_views_taken_before_stay_valid():
    """A cube pressed between two plates breaks into fragments (docs/breakage.md):
    the world gains bodies, keeps its volume, and views of its bodies taken
    before the run still alias them (the builder reserved room for every
    fragment)."""
    s = gjkdem.Settings()
    s.gravity = [0, 0, 0]
    s.model = "volume"
    b = gjkdem.WorldBuilder(s)
    b.add_material("rock", density=2500, youngs_modulus=1e7, strength=2e4, weibull_modulus=5,
                   strength_size=0.0124, unbreakable_below=0.0055, strength_seed=3)
    down = b.add_motion(velocity=[0, 0, -0.05])
    b.add_plane([0, 0, 0], [0, 0, 1], "rock")
    b.add_plane([0, 0, 0.01001], [0, 0, -1], "rock", motion=down)
    b.add_body(gjkdem.Shape("box", half_extents=[0.005] * 3), "rock", position=[0, 0, 0.005])
    w = b.build()
    before = w.positions
    dt = w.critical_time_step()
    w.run(0.003, dt=dt)
    assert w.grains_broken >= 3
    assert w.body_count == 1 + w.grains_broken
    assert before.ctypes.data == w.positions.ctypes.data  # the same memory: no reallocation
    assert len(set(w.ids.tolist())) == w.body_count
    e = w.energies()  # the splits stored energy in the fragments' contacts: the balance counts it
    assert e["split_energy"] > 0
    assert e["wall_work"] + e["split_energy"] >= e["kinetic"] + e["elastic"]
    with pytest.raises(ValueError, match="unbreakable_below"):
        gjkdem.WorldBuilder(s).add_material("weak", density=2500, youngs_modulus=1e7, strength=1e4,
                                            strength_size=0.01)


def test_a_bonded_assembly_cracks_when_dropped_and_its_bad_values_are_refused():
    """A box cut into 12 glued pieces (docs/breakage.md): it holds together
    resting on a floor and cracks, some bonds and not all, dropped at 1 m/s;
    bad pieces, seeds and glue are ValueErrors naming the key."""
    def drop(speed):
        s = gjkdem.Settings()
        s.model = "volume"
        b = gjkdem.WorldBuilder(s)
        b.add_material("rock", density=2500, youngs_modulus=1e7, bond_tensile_strength=3e4,
                       bond_shear_strength=3e4, bond_damping=0.2)
        b.add_plane([0, 0, 0], [0, 0, 1], "rock")
        pieces = b.add_bonded(gjkdem.Shape("box", half_extents=[0.01, 0.006, 0.008]), "rock", pieces=12, seed=5,
                              position=[0, 0, 0.0081], velocity=[0.01, 0, -speed])
        assert list(pieces) == list(range(12))
        return b.build()
    w = drop(0.0)
    w.run(0.005, dt=w.critical_time_step())
    assert w.bonds >= 11 and w.bonds_broken == 0
    w = drop(1.0)
    w.run(0.02, dt=w.critical_time_step())
    assert 0 < w.bonds_broken < w.bonds
    b = gjkdem.WorldBuilder()
    b.add_material("rock", density=2500, youngs_modulus=1e7, bond_tensile_strength=3e4, bond_shear_strength=3e4)
    box = gjkdem.Shape("box", half_extents=[0.01] * 3)
    for kwargs, key in [({"pieces": 1}, "pieces"), ({"pieces": -5}, "pieces"), ({"pieces": 4, "seed": -1}, "seed"),
                        ({"pieces": 4, "relaxations": 1000}, "relaxations")]:
        with pytest.raises(ValueError, match=key):
            b.add_bonded(box, "rock", **kwargs)
    with pytest.raises(ValueError, match="bond_shear_strength"):
        b.add_material("half", density=2500, youngs_modulus=1e7, bond_tensile_strength=3e4)
    with pytest.raises(ValueError, match="bond_moment_strength"):
        b.add_material("bent", density=2500, youngs_modulus=1e7, bond_tensile_strength=3e4, bond_shear_strength=3e4,
                       bond_moment_strength=-1)
    b.add_material("plain", density=2500, youngs_modulus=1e7)
    with pytest.raises(ValueError, match="no glue"):
        b.add_bonded(box, "plain", pieces=4)


def test_a_region_fill_of_bonded_assemblies_cuts_each_of_its_own():
    """fill_region(pieces=N) makes bonded assemblies: each of N pieces
    tiling its box, each cut from its own sites and glued into one; bad
    pieces are ValueErrors naming the key."""
    b = gjkdem.WorldBuilder(gjkdem.Settings())
    b.add_material("rock", density=2000, youngs_modulus=1e7, bond_tensile_strength=3e4, bond_shear_strength=3e4)
    box = gjkdem.Shape("box", half_extents=[0.01, 0.008, 0.006])
    placed = b.fill_region([box], 5, lo=[-0.05, -0.05, 0], hi=[0.05, 0.05, 0.05], material="rock", pieces=7)
    assert len(placed) == 35
    with pytest.raises(ValueError, match="pieces"):
        b.fill_region([box], 2, lo=[-0.05, -0.05, 0.1], hi=[0.05, 0.05, 0.2], material="rock", pieces=1)
    with pytest.raises(ValueError, match="fixed"):
        b.fill_region([box], 2, lo=[-0.05, -0.05, 0.1], hi=[0.05, 0.05, 0.2], material="rock", pieces=4, fixed=True)
    w = b.build()
    masses = w.masses()
    for k in range(5):  # the pieces of each assembly add up to its box's mass
        assert abs(masses[7 * k:7 * k + 7].sum() / (2000 * 0.02 * 0.016 * 0.012) - 1) < 1e-12
    assert len({round(float(m), 12) for m in masses[:7]} ^ {round(float(m), 12) for m in masses[7:14]}) > 0
    assert w.bonds >= 5 * 6  # each assembly's pieces are glued into one
