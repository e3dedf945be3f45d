"""The Python module under attack (issue 32): input that once crashed the
interpreter or was silently ignored is refused with an exception, whole
classes at a time: nesting and self-reference, integers beyond 64 bits,
lists emptied by another thread during a batch, one World used by two
threads, settings a scene refuses, scenes nested too deep."""
import math
import threading

import numpy as np
import pytest

import gjkdem


@pytest.mark.parametrize("depth", [65, 1000, 50000])
def test_nesting_deeper_than_the_query_format_reads_is_refused(depth):
    nested = [0.0, 0.0, 0.0]
    for _ in range(depth):
        nested = [nested]
    with pytest.raises(ValueError, match="nested deeper than 64"):
        gjkdem.Shape("polytope", vertices=nested)
    with pytest.raises(ValueError, match="nested deeper than 64"):
        gjkdem.Shape.from_json({"type": "sphere", "radius": 1.0, "center": nested})
    with pytest.raises(ValueError, match="nested deeper than 64"):
        gjkdem.Shape.from_json('{"type": "sphere", "radius": 1, "center": ' + "[" * depth + "]" * depth + "}")


def test_a_list_or_dict_holding_itself_is_refused():
    looped = []
    looped.append(looped)
    with pytest.raises(ValueError, match="holds itself"):
        gjkdem.Shape("polytope", vertices=looped)
    d = {"type": "sphere", "radius": 1.0}
    d["center"] = d
    with pytest.raises(ValueError, match="holds itself"):
        gjkdem.Shape.from_json(d)


def test_integers_beyond_64_bits_are_numbers_or_a_plain_error():
    big = gjkdem.Shape("sphere", radius=2**64)  # read as the nearest double
    assert math.isclose(big.volume, 4 / 3 * math.pi * 2.0**192, rel_tol=1e-12)
    with pytest.raises(ValueError) as e:
        gjkdem.Shape("sphere", radius=10**400)
    assert "too large" in str(e.value) and "cast" not in str(e.value)


def test_a_list_emptied_by_another_thread_during_a_batch_does_not_crash():
    rng = np.random.default_rng(3)
    made = [gjkdem.Shape("polytope", vertices=rng.normal(size=(12, 3))) for _ in range(4000)]
    poses = np.tile([0.0, 0, 0, 1, 0, 0, 0], (len(made), 1))
    poses[:, 0] = np.linspace(-3, 3, len(made))
    one = gjkdem.Shape("sphere", radius=0.5)
    for _ in range(5):
        shapes = list(made)
        stop = threading.Event()

        def empty_it():
            while not stop.is_set():  # runs whenever the batch lets the GIL go
                shapes.clear()

        t = threading.Thread(target=empty_it)
        t.start()
        try:
            result = gjkdem.distance_batch(shapes, one, poses, None)
            assert len(result["distance"]) == len(poses) and np.all(np.isfinite(result["distance"]))
        except ValueError as e:  # emptied before the batch read it
            assert "empty" in str(e) or "one entry per pair" in str(e)
        finally:
            stop.set()
            t.join()


def small_world():
    b = gjkdem.WorldBuilder()
    b.add_material("m", 2500, 1e7)
    b.add_plane([0, 0, 0], [0, 0, 1], "m")
    b.add_body(gjkdem.Shape("sphere", radius=0.01), "m", position=[0, 0, 0.05])
    return b.build()


def test_a_world_running_in_one_thread_refuses_another_threads_calls():
    w = small_world()
    inside, go_on = threading.Event(), threading.Event()

    def observer(world, state):
        if state.outputs == 2:
            inside.set()
            go_on.wait(10)  # the GIL is free meanwhile: the other thread calls in

    runner = threading.Thread(target=lambda: w.run(0.02, dt=1e-5, output_every=0.005, observer=observer))
    runner.start()
    assert inside.wait(30)
    try:
        for call in (lambda: w.run(0.01, dt=1e-5), lambda: w.step(1e-5), w.contacts, w.energies,
                     lambda: w.set_positions(np.zeros((1, 3)))):
            with pytest.raises(RuntimeError, match="another thread"):
                call()
    finally:
        go_on.set()
        runner.join()
    w.step(1e-5)  # free again once the run is over


def test_a_run_from_its_own_observer_is_refused():
    w = small_world()
    said = []

    def observer(world, state):
        if state.outputs == 1:
            try:
                world.run(0.001, dt=1e-5)
            except RuntimeError as e:
                said.append(str(e))

    w.run(0.002, dt=1e-5, observer=observer)
    assert said and "already being stepped or run" in said[0]


@pytest.mark.parametrize(
    "name, value",
    [("tessellation", 10**9), ("tessellation", 4), ("volume_stiffness", float("nan")), ("volume_stiffness", -1.0),
     ("linear_stiffness", -5.0), ("threads", -7), ("threads", 5000), ("box_skin", -0.1)],
)
def test_settings_a_scene_refuses_python_refuses_at_once(name, value):
    s = gjkdem.Settings()
    before = getattr(s, name)
    with pytest.raises(ValueError, match=name):
        setattr(s, name, value)
    assert getattr(s, name) == before or (isinstance(before, float) and math.isnan(before))


def test_settings_made_bad_behind_the_setters_are_refused_by_the_builder():
    s = gjkdem.Settings()
    s.periodic = {"x": (0.1, 0.0)}
    with pytest.raises(gjkdem.BuildError, match="periodic.x must be"):
        gjkdem.WorldBuilder(s)


@pytest.mark.parametrize("text", ["[" + "a." * 50000 + "b]\n", "a" + ".a" * 50000 + " = 1\n",
                                  "x = { " + "a." * 50000 + "b = 1 }\n"])
def test_a_scene_nested_thousands_deep_is_refused(text):
    with pytest.raises(gjkdem.SceneError, match="nested deeper than 64 levels"):
        gjkdem.load_scene_text(text)


def test_poses_beyond_the_supported_range_are_refused_as_shape_fields_are():
    s = gjkdem.Shape("sphere", radius=1.0)
    far = [1e200, 0, 0, 1, 0, 0, 0]
    with pytest.raises(ValueError, match="supported range"):
        gjkdem.distance(s, s, None, far)
    with pytest.raises(ValueError, match="supported range"):
        gjkdem.distance_batch(s, s, None, np.array([far]))


def test_an_empty_pose_array_counts_as_zero_pairs():
    s = gjkdem.Shape("sphere", radius=1.0)
    five = np.tile([3.0, 0, 0, 1, 0, 0, 0], (5, 1))
    with pytest.raises(ValueError, match="one entry per pair"):
        gjkdem.distance_batch(s, s, np.zeros((0, 7)), five)
    empty = gjkdem.distance_batch(s, s, np.zeros((0, 7)), np.zeros((0, 7)))
    assert len(empty["distance"]) == 0


@pytest.mark.parametrize("field, value", [("periodic", {"x": "ab"}), ("periodic", {"x": (0.0, "1")}),
                                          ("cell_control", {"stress": {"x": "high"}}),
                                          ("cell_control", {"stress": 5})])
def test_settings_of_the_wrong_type_say_what_they_expect(field, value):
    s = gjkdem.Settings()
    with pytest.raises(ValueError) as e:
        setattr(s, field, value)
    assert field in str(e.value) and "expected" in str(e.value) and "cast" not in str(e.value).lower()


def test_a_periodic_range_beyond_the_supported_range_is_refused_by_name():
    s = gjkdem.Settings()
    s.periodic = {"x": (-1e308, 1e308)}
    with pytest.raises(gjkdem.BuildError, match="periodic.x must lie within"):
        gjkdem.WorldBuilder(s)


def test_the_depth_check_reads_multi_line_strings_as_toml_does():
    deep = "[" + "a." * 50000 + "b]\n"
    with pytest.raises(gjkdem.SceneError, match="nested deeper than 64 levels"):  # a quote inside """ ends nothing
        gjkdem.load_scene_text('x = """say "hi" now"""\n' + deep)
    # Dots and braces inside a literal multi-line string are not keys: the
    # scene is read on, and refused for what it lacks, not for its depth.
    text = "[simulation]\nduration = 1.0\nnote = '''\n" + "a." * 100 + "{ [\n'''\n"
    with pytest.raises(gjkdem.SceneError) as e:
        gjkdem.load_scene_text(text)
    assert "nested deeper" not in str(e.value)
