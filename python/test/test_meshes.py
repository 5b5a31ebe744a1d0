"""simit.load_mesh on TetGen, Gmsh and OBJ files, 0-based whatever the
file's numbering, and meshes made into sets."""

import numpy as np
import pytest

import simit

from conftest import RUN_INPUTS, SHARED

GMSH = """$MeshFormat
2.2 0 8
$EndMeshFormat
$Nodes
4
7 0 0 0
8 2 0 0
9 0 2 0
10 0 0 2
$EndNodes
$Elements
2
1 1 2 0 1 7 8
2 4 2 0 1 7 8 9 10
$EndElements
"""

# A unit square as one quad (fan-triangulated from its first vertex) and a
# triangle given with negative (relative) indices and v/vt/vn forms.
OBJ = """v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
f 1 2 3 4
f -5/1/1 -4/2/2 -1/3/3
"""


def test_tetgen():
    mesh = simit.load_mesh(RUN_INPUTS / "tet.node")
    np.testing.assert_array_equal(mesh.points, [[0, 0, 0], [1, 0, 0],
                                                [0, 1, 0], [0, 0, 1]])
    np.testing.assert_array_equal(mesh.tets, [[0, 1, 2, 3]])
    assert mesh.edges.shape == (0, 2)


def test_gmsh(tmp_path):
    (tmp_path / "m.msh").write_text(GMSH)
    mesh = simit.load_mesh(tmp_path / "m.msh")
    np.testing.assert_array_equal(mesh.points[3], [0, 0, 2])
    np.testing.assert_array_equal(mesh.edges, [[0, 1]])
    np.testing.assert_array_equal(mesh.tets, [[0, 1, 2, 3]])


def test_obj(tmp_path):
    (tmp_path / "m.obj").write_text(OBJ)
    mesh = simit.load_mesh(tmp_path / "m.obj")
    assert mesh.points.shape == (5, 3)
    np.testing.assert_array_equal(mesh.triangles,
                                  [[0, 1, 2], [0, 2, 3], [0, 1, 4]])


def test_mesh_errors_carry_the_file_and_line(tmp_path):
    (tmp_path / "bad.node").write_text("2 3 0 0\n0 0 0 0\n1 x 0 0\n")
    with pytest.raises(simit.Error) as info:
        simit.load_mesh(tmp_path / "bad.node")
    assert info.value.file == str(tmp_path / "bad.node")
    assert info.value.line == 3


def test_refined_tets_keep_the_volume():
    mesh = simit.load_mesh(RUN_INPUTS / "tet.node").refined()
    assert mesh.tets.shape == (8, 4) and mesh.points.shape == (10, 3)
    corners = mesh.points[mesh.tets]
    volumes = np.linalg.det(corners[:, 1:] - corners[:, :1]) / 6
    np.testing.assert_allclose(np.abs(volumes).sum(), 1 / 6, rtol=1e-14)


def test_sets_from_mesh():
    mesh = simit.load_mesh(SHARED / "data" / "meshes" / "bunny.1.node")
    points, springs = simit.sets_from_mesh(mesh, "edges", name="springs")
    assert (len(points), len(springs)) == (3607, 19233)
    np.testing.assert_array_equal(points["x"], mesh.points)
    np.testing.assert_array_equal(springs.endpoints, mesh.edges)


def test_sets_from_mesh_names_the_element_kinds():
    mesh = simit.load_mesh(RUN_INPUTS / "tet.node")
    with pytest.raises(ValueError, match="'edges', 'triangles' or 'tets', not 'hexes'"):
        simit.sets_from_mesh(mesh, "hexes")
