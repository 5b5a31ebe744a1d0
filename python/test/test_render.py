"""simit.render: the surface of a tet mesh, and PNG frames of a scene."""

import json

import matplotlib.image
import numpy as np

import simit
from simit import render

from conftest import RUN_INPUTS


def test_boundary_faces_drop_shared_faces_and_face_outwards():
    points = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1],
                       [1, 1, 1]], dtype=float)
    # Two positively oriented tets sharing the face (1, 2, 3).
    tets = np.array([[0, 1, 2, 3], [4, 3, 2, 1]])
    for tet in tets:
        corners = points[tet]
        assert np.linalg.det(corners[1:] - corners[0]) > 0
    faces = render.boundary_faces(tets)
    assert len(faces) == 6
    assert not any(set(face) == {1, 2, 3} for face in faces)
    centre = points.mean(axis=0)
    for face in faces:
        a, b, c = points[face]
        normal = np.cross(b - a, c - a)
        assert normal @ ((a + b + c) / 3 - centre) > 0


def test_frames_of_a_tet_scene_are_drawn(tmp_path):
    with open(RUN_INPUTS / "fem-tet.json") as f:
        description = json.load(f)
    description["frames"] = 2
    description["outputs"] = [
        {"format": "vtk", "path": "tet_{frame}.vtu", "set": "verts",
         "cells": "tets", "fields": ["v"]}]
    simit.Scene(description, directory=RUN_INPUTS,
                output_dir=tmp_path / "out").run()
    files = sorted(str(p) for p in (tmp_path / "out").glob("*.vtu"))
    pngs = render.render(files, "v", tmp_path / "png", dpi=50)
    assert [p.rsplit("/", 1)[1] for p in pngs] == \
        ["tet_0.png", "tet_1.png", "tet_2.png"]
    image = matplotlib.image.imread(pngs[-1])
    assert image.shape[:2] == (240, 320)
    assert image[..., :3].std() > 0.01  # something was drawn
