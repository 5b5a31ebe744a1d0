"""Simit from Python: compile Simit programs, bind NumPy-backed sets, run
scenes (docs/python.md).

    import simit
    program = simit.compile("examples/springs/springs.sim")
    points = simit.Set("points", size=2)
    points["x"] = [[0, 0, 0], [1, 0, 0]]
    springs = simit.Set("springs", [points, points], endpoints=[[0, 1]])
    program.step.bind(points=points, springs=springs, h=0.01, ...)
    program.step()
"""

import os
from collections.abc import Mapping

import numpy as np

from .errors import Error, NumericsError
from ._simit import (Function, Mesh, Program, Scene, Set, load_mesh,
                     phase_times, reset_phase_times)

__all__ = ["Error", "NumericsError", "Function", "Mesh", "Program", "Scene",
           "Set", "compile", "load_mesh", "phase_times", "reset_phase_times",
           "sets_from_mesh"]


class ExternArrays(Mapping):
    """A scene's extern tensors by name, each an array over the scene's own
    storage. Assigning writes into that array, as `externs["h"][()] = 0.005`
    does: `externs["h"] = 0.005` (a value that does not fit the dtype or
    the shape is an error, never a silently unbound copy)."""

    def __init__(self, arrays):
        self._arrays = arrays

    def __getitem__(self, name):
        return self._arrays[name]

    def __iter__(self):
        return iter(self._arrays)

    def __len__(self):
        return len(self._arrays)

    def __setitem__(self, name, value):
        if name not in self._arrays:
            raise KeyError(f"the scene's program reads no extern tensor "
                           f"{name!r}")
        np.copyto(self._arrays[name], value, casting="same_kind")


_scene_externs = Scene.externs
Scene.externs = property(
    lambda self: ExternArrays(_scene_externs.fget(self)),
    doc="{name: array} over the extern tensors the program reads; "
        "assigning to a name writes into its array.")


def _is_path(program):
    if isinstance(program, os.PathLike):
        return True
    return "\n" not in program and program.strip().endswith((".sim", ".mlir"))


def compile(program, *, name=None, float32=False, time=False,
            check_numerics=False, host_functions=(), threads=0,
            target="cpu"):
    """A Program from a .sim or .mlir file, or from Simit source text.

    `name` names source text in error messages (default "<string>"; a name
    ending in .mlir loads the text as MLIR). float32 compiles Simit's float
    as single precision; time brackets assemblies and solves with the phase
    timer (phase_times()); check_numerics makes calls raise NumericsError at
    the first NaN or infinity an assembly or solve produces. threads runs
    the set loops on that many threads (0: $SIMIT_NUM_THREADS, else every
    core); the results are the same for every count. target "gpu" runs the
    set loops as CUDA kernels (docs/gpu.md); without a CUDA device the first
    call raises an error that says why.
    """
    result = Program(float32=float32, time=time,
                     check_numerics=check_numerics,
                     host_functions=list(host_functions), threads=threads,
                     target=target)
    if _is_path(program):
        result.load_file(program)
    elif name is not None and name.endswith(".mlir"):
        result.load_mlir(program, name)
    else:
        result.load_string(program, name or "<string>")
    return result


def sets_from_mesh(mesh, elements="tets", *, points="points", name=None):
    """A vertex set of the mesh's points (field "x" holding their
    coordinates) and an edge set of its "edges", "triangles" or "tets"."""
    if elements not in ("edges", "triangles", "tets"):
        raise ValueError("elements must be 'edges', 'triangles' or 'tets', "
                         f"not {elements!r}")
    point_set = Set(points, size=len(mesh.points))
    point_set["x"] = mesh.points
    indices = getattr(mesh, elements)
    element_set = Set(name or elements, [point_set] * indices.shape[1],
                      endpoints=indices)
    return point_set, element_set
