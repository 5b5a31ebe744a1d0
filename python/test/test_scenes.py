"""simit.Scene: scenes from JSON files and dicts, against the closed form of
test/Run/springs-pair.test; their .vtu outputs read back by meshio."""

import glob
import json
import os

import meshio
import numpy as np
import pytest

import simit
from simit import vtu

from conftest import RUN_INPUTS

PAIR = RUN_INPUTS / "springs-pair.json"


def pair_motion(steps):
    """Velocity and height of both points of springs-pair after each step
    (m = 1, visc = 2, g = -10): (m + h visc) v' = m v + h m g."""
    v = y = 0.0
    for h in steps:
        v = (v + h * -10.0) / (1.0 + h * 2.0)
        y += h * v
    return v, y


def test_a_scene_file_runs_as_simit_run_runs_it():
    scene = simit.Scene(PAIR)
    times = scene.run()
    assert scene.frame == scene.frames == 2
    v, y = pair_motion([0.1, 0.1])
    points = scene.sets["points"]
    np.testing.assert_allclose(points["v"][:, 1], [v, v], rtol=1e-12)
    np.testing.assert_allclose(points["x"][:, 1], [y, y], rtol=1e-12)
    np.testing.assert_allclose(points["m"], [1.0, 1.0], rtol=1e-12)
    assert times["frames"] == 2
    assert len(times["per_frame"]["frame_ms"]) == 2
    assert {"compile_ms", "bind_ms", "sets_ms", "init_ms", "frame_ms",
            "first_frame_ms", "assembly_ms", "solve_ms"} <= set(times)


def test_a_scene_dict_with_the_file_directory():
    with open(PAIR) as f:
        description = json.load(f)
    description["frames"] = 1
    scene = simit.Scene(description, directory=RUN_INPUTS)
    scene.run()
    v, y = pair_motion([0.1])
    np.testing.assert_allclose(scene.sets["points"]["x"][:, 1], [y, y],
                               rtol=1e-12)


def test_externs_written_between_frames_are_read_by_the_next_one():
    scene = simit.Scene(PAIR, frames=3)
    scene.step()
    scene.externs["h"][()] = 0.05
    scene.step(2)
    v, y = pair_motion([0.1, 0.05, 0.05])
    np.testing.assert_allclose(scene.sets["points"]["x"][:, 1], [y, y],
                               rtol=1e-12)


def test_assigning_an_extern_writes_into_its_array():
    scene = simit.Scene(PAIR, frames=3)
    scene.step()
    scene.externs["h"] = 0.05
    assert scene.externs["h"] == 0.05
    scene.step(2)
    v, y = pair_motion([0.1, 0.05, 0.05])
    np.testing.assert_allclose(scene.sets["points"]["x"][:, 1], [y, y],
                               rtol=1e-12)
    with pytest.raises(KeyError, match="no extern tensor 'hh'"):
        scene.externs["hh"] = 1.0
    with pytest.raises(ValueError):
        scene.externs["h"] = [1.0, 2.0]


def test_externs_marked_constant_are_not_folded_in_python():
    # Python may write any extern between frames: a Scene folds none
    # (docs/scene-specialisation.md), not even those marked constant.
    with open(PAIR) as f:
        description = json.load(f)
    description["externs"]["h"] = {"value": 0.1, "constant": True}
    description["frames"] = 3
    scene = simit.Scene(description, directory=RUN_INPUTS)
    scene.step()
    scene.externs["h"][()] = 0.05
    scene.step(2)
    v, y = pair_motion([0.1, 0.05, 0.05])
    np.testing.assert_allclose(scene.sets["points"]["x"][:, 1], [y, y],
                               rtol=1e-12)


def test_time_splits_frames_into_assembly_and_solve():
    scene = simit.Scene(PAIR, time=True)
    times = scene.run()
    per_frame = times["per_frame"]
    for i in range(2):
        assert 0 <= per_frame["assembly_ms"][i] + per_frame["solve_ms"][i] \
            <= per_frame["frame_ms"][i]


def vtk_scene(tmp_path):
    """springs-pair with a .vtu output per frame of the points, springs and v."""
    with open(PAIR) as f:
        description = json.load(f)
    description["outputs"] = [
        {"format": "vtk", "path": "pair_{frame}.vtu", "set": "points",
         "cells": "springs", "fields": ["v", "m"]}]
    return simit.Scene(description, directory=RUN_INPUTS,
                       output_dir=tmp_path)


def test_vtu_outputs_read_by_meshio_hold_the_sets(tmp_path):
    scene = vtk_scene(tmp_path)
    scene.run()
    files = sorted(glob.glob(str(tmp_path / "pair_*.vtu")))
    assert [os.path.basename(f) for f in files] == \
        ["pair_0.vtu", "pair_1.vtu", "pair_2.vtu"]
    assert scene.written_files == [str(tmp_path / f"pair_{i}.vtu")
                                   for i in range(3)]
    mesh = meshio.read(tmp_path / "pair_2.vtu")
    points = scene.sets["points"]
    np.testing.assert_array_equal(mesh.points, points["x"])
    np.testing.assert_array_equal(mesh.point_data["v"], points["v"])
    # meshio reads a one-component array as (n, 1).
    np.testing.assert_array_equal(mesh.point_data["m"][:, 0], points["m"])
    assert [block.type for block in mesh.cells] == ["line"]
    np.testing.assert_array_equal(mesh.cells[0].data,
                                  scene.sets["springs"].endpoints)


def test_simit_vtu_reads_what_meshio_reads(tmp_path):
    vtk_scene(tmp_path).run()
    for path in glob.glob(str(tmp_path / "*.vtu")):
        ours, theirs = vtu.read(path), meshio.read(path)
        np.testing.assert_array_equal(ours.points, theirs.points)
        np.testing.assert_array_equal(ours.cells[2], theirs.cells[0].data)
        for name, values in theirs.point_data.items():
            np.testing.assert_array_equal(ours.point_data[name],
                                          values.reshape(ours.point_data[name].shape))


def test_scene_errors_name_the_scene_and_the_json_path():
    with pytest.raises(simit.Error, match="sets.points.fields.x") as info:
        simit.Scene({"sets": {"points": {"size": 2, "fields": {"x": "?"}}}})
    assert info.value.file == "<scene dict>"
    with pytest.raises(simit.Error) as info:
        simit.Scene(RUN_INPUTS / "no-such-scene.json")
    assert info.value.file.endswith("no-such-scene.json")


def test_the_same_bits_on_one_and_two_threads():
    """fem-bar (Neo-Hookean, 2k tets: several chunks and colours) gives
    bit-identical positions on one and on two threads (docs/threads.md)."""
    positions = []
    for threads in (1, 2):
        scene = simit.Scene(RUN_INPUTS / "fem-bar-converged.json", frames=2,
                            threads=threads)
        scene.run()
        positions.append(np.array(scene.sets["verts"]["x"]))
    assert positions[0].tobytes() == positions[1].tobytes()
    assert not np.array_equal(positions[0], np.zeros_like(positions[0]))


def test_threads_must_be_positive():
    with pytest.raises(simit.Error, match="number of threads must be positive"):
        simit.Scene(PAIR, threads=-1)


def test_frame_counts_must_not_be_negative():
    with pytest.raises(simit.Error, match="frames: expected a frame count of "
                       "at least 0, not -1"):
        simit.Scene(PAIR, frames=-1)
    scene = simit.Scene(PAIR, frames=0)
    with pytest.raises(simit.Error, match="step: expected a frame count of "
                       "at least 0, not -2"):
        scene.step(-2)
