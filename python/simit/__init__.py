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

from .errors import Error, NumericsError
from ._simit import (Function, Mesh, Program, Scene, Set, load_mesh,
                     phase_times, reset_phase_times)

__all__ = ["Error", "NumericsError", "Function", "Mesh", "Program", "Scene",
           "Set", "compile", "load_mesh", "phase_times", "reset_phase_times",
           "sets_from_mesh"]


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
