"""A scene run from Python writes the same bytes as `gjkdem run` of the same
scene (both go through io::SceneRun), stops and resumes, and reports bad
scenes and folders with the program's messages."""
import json
import shutil
import subprocess

import numpy as np
import pytest

import gjkdem

# (checkpoint.bin holds the wall time of the run, so it differs between any two
# runs; a resumed run ending with these bytes shows what it holds is the same.)
SAME_BYTES = ["trace.csv", "energy.csv", "scene.toml", "frames/frame_000003.vtk", "frames/frame_000006.vtk",
              "frames/frames.vtk.series"]


@pytest.fixture
def scene(repo, tmp_path):
    src = repo / "tests" / "data" / "scenes"
    for name in ("small_pour.toml", "chute.obj"):
        shutil.copy(src / name, tmp_path / name)
    return tmp_path / "small_pour.toml"


def test_a_scene_run_from_python_gives_the_programs_bytes(cli, scene, tmp_path):
    by_cli = tmp_path / "cli"
    run = subprocess.run([cli, "run", str(scene), "--out", str(by_cli), "--threads", "1", "--quiet"],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    by_python = tmp_path / "python"
    outputs = []
    r = gjkdem.SceneRun(str(scene), out=str(by_python), threads=1)
    status = r.run(observer=lambda world, state: outputs.append(state.step))
    assert status == "completed"
    assert outputs == [0, 100, 200, 300, 400, 500, 600]
    for name in SAME_BYTES:
        assert (by_python / name).read_bytes() == (by_cli / name).read_bytes(), name
    info = json.loads((by_python / "run.json").read_text())
    assert info["status"] == "completed" and info["steps"] == 600


def test_a_new_run_starts_from_a_finished_one_with_other_materials_not_other_bodies(scene, tmp_path):
    settle = tmp_path / "settle"
    assert gjkdem.SceneRun(str(scene), out=str(settle), threads=1).run() == "completed"
    text = scene.read_text()
    study = scene.parent / "study.toml"
    study.write_text(text.replace("friction = 0.5", "friction = 0.1").replace("duration = 0.06", "duration = 0.02"))
    r = gjkdem.SceneRun(str(study), out=str(tmp_path / "study"), threads=1, start_from=str(settle))
    assert r.world.time == 0
    ended = gjkdem.load_run(str(settle)).world
    assert np.array_equal(r.world.positions, ended.positions)
    assert r.run() == "completed"
    changed = scene.parent / "changed.toml"
    changed.write_text(text.replace('name = "octahedron"', 'name = "cube"'))
    with pytest.raises(gjkdem.CheckpointError, match=r"\('tracer'\) has another shape"):
        gjkdem.SceneRun(str(changed), out=str(tmp_path / "changed"), start_from=str(settle))


def test_a_runs_state_exported_as_a_scene_starts_where_it_ended(scene, tmp_path):
    settle = tmp_path / "settle"
    assert gjkdem.SceneRun(str(scene), out=str(settle), threads=1).run() == "completed"
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    text = gjkdem.export_scene(str(settle), path=str(elsewhere / "bed.toml"))
    assert (elsewhere / "bed.toml").read_text() == text
    bed = gjkdem.load_scene(str(elsewhere / "bed.toml")).world  # the chute's file found from elsewhere
    ended = gjkdem.load_run(str(settle)).world
    moving = ended.fixed == 0
    assert bed.positions.shape == ended.positions.shape
    np.testing.assert_allclose(bed.positions[moving], ended.positions[moving], rtol=0, atol=1e-14)
    np.testing.assert_allclose(bed.velocities[moving], ended.velocities[moving], rtol=0, atol=1e-12)
    assert bed.names == ended.names
    with pytest.raises(gjkdem.SceneError, match="run.json"):
        gjkdem.export_scene(str(tmp_path))


def test_a_stopped_python_run_resumes_to_the_same_bytes(cli, scene, tmp_path):
    whole = tmp_path / "whole"
    assert gjkdem.SceneRun(str(scene), out=str(whole), threads=1).run() == "completed"
    parts = tmp_path / "parts"
    assert gjkdem.SceneRun(str(scene), out=str(parts), threads=1).run(stop_after=250) == "stopped"
    assert not gjkdem.SceneRun.completed(str(parts))
    assert json.loads((parts / "run.json").read_text())["stopped_by"] == "stop_after"
    assert gjkdem.SceneRun.resume(str(parts), threads=2).run() == "completed"
    for name in SAME_BYTES:
        assert (parts / name).read_bytes() == (whole / name).read_bytes(), name
    assert gjkdem.SceneRun.completed(str(parts))


def test_the_world_of_a_scene_is_there_to_read(scene):
    s = gjkdem.load_scene(str(scene))
    assert s.world.positions.shape == (s.world.body_count, 3)
    assert (s.world.fixed == 0).sum() == 81  # the tracer and two generators of 60 and 20
    assert s.dt == 1e-4 and s.duration == 0.06
    assert s.resolved["contact"]["model"] == "volume"


@pytest.mark.parametrize(
    "text, message",
    [
        ("[simulation]\nduration = -1.0\n", "duration"),
        ("[simulation]\nduration = 1.0\n[[material]]\nname = \"m\"\ndensity = 1.0\nyoungs_modulus = 1.0\n"
         "friction = -0.5\n", "friction: must be >= 0"),
        ("[simulation\n", "line 1"),
    ],
)
def test_bad_scenes_raise_scene_error_with_the_programs_message(text, message):
    with pytest.raises(gjkdem.SceneError) as e:
        gjkdem.load_scene_text(text)
    assert message in str(e.value)
    assert issubclass(gjkdem.SceneError, ValueError)


def test_a_folder_holding_another_run_is_refused(scene, tmp_path):
    out = tmp_path / "taken"
    gjkdem.SceneRun(str(scene), out=str(out), threads=1).run(stop_after=10)
    with pytest.raises(gjkdem.RunFolderError) as e:
        gjkdem.SceneRun(str(scene), out=str(out))
    assert "overwrite" in str(e.value)
    assert isinstance(e.value, OSError)
    with pytest.raises(gjkdem.SceneError, match="cannot read"):
        gjkdem.SceneRun(str(tmp_path / "missing.toml"), out=str(tmp_path / "x"))


def test_check_scene_is_the_programs_dry_run(cli, scene, tmp_path):
    d = gjkdem.check_scene(str(scene), threads=1, sample_seconds=0.2)
    assert d["bodies"] == d["moving"] + d["fixed"] and d["moving"] == 81 and d["failure"] is None
    assert d["steps"] == 600 and d["outputs"] == 7 and 0 < d["sampled_steps"] <= 600
    assert d["estimated_seconds"] > 0 and d["estimated_bytes"] > 7 * d["output_bytes"] > 0
    assert not (tmp_path / "small_pour_out").exists() and not (scene.parent / "small_pour_out").exists()
    printed = subprocess.run([cli, "run", "--check", str(scene), "--threads", "1"], capture_output=True, text=True)
    assert printed.returncode == 0 and printed.stdout.splitlines()[:2] == d["summary"].splitlines()[:2]
    with pytest.raises(gjkdem.SceneError, match="cannot read"):
        gjkdem.check_scene(str(tmp_path / "missing.toml"))
    with pytest.raises(ValueError, match="sample_seconds"):
        gjkdem.check_scene(str(scene), sample_seconds=float("nan"))
