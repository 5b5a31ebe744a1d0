"""Errors of the compiler and runtime as simit.Error with their position;
misuse of the Python API as the usual Python exceptions."""

import numpy as np
import pytest

import simit

from conftest import SPRINGS_SIM

UNDEFINED = """element P
  x : float;
end
extern ps : set{P};

export func f()
  ps.x = 2.0 * y;
end
"""


def test_a_frontend_error_carries_file_line_and_column():
    with pytest.raises(simit.Error) as info:
        simit.compile(UNDEFINED, name="bad.sim")
    error = info.value
    assert (error.file, error.line, error.column) == ("bad.sim", 7, 16)
    assert "error:" in error.message and "'y'" in error.message


def test_a_lowering_error_carries_its_first_position():
    program = simit.compile("element V\n  c : complex;\nend\n"
                            "element E\nend\n"
                            "extern vs : set{V};\n"
                            "extern es : set{E}(vs, vs);\n"
                            "func f(e : E, v : (V*2)) -> "
                            "(K : matrix[vs,vs](complex))\n"
                            "  K(v(0),v(1)) = createComplex(1.0, 0.0);\nend\n"
                            "export func solve()\n"
                            "  K = map f to es reduce +;\n"
                            "  vs.c = K \\ vs.c;\nend\n", name="c.sim")
    with pytest.raises(simit.Error) as info:
        program.solve()
    error = info.value
    assert error.message.startswith("lowering failed")
    assert (error.file, error.line, error.column) == ("c.sim", 13, 12)


def test_a_missing_file():
    with pytest.raises(simit.Error) as info:
        simit.compile("no/such/program.sim")
    assert info.value.file == "no/such/program.sim"


def test_unknown_functions():
    program = simit.compile(SPRINGS_SIM)
    assert program.functions == ["init", "step"]
    with pytest.raises(AttributeError, match="no function 'stepp'"):
        program.stepp
    with pytest.raises(simit.Error, match="exported functions: init, step"):
        program["stepp"]


def springs_sets(x_shape=3):
    points = simit.Set("points", size=2)
    points.add_field("x", shape=x_shape)
    points.add_field("v", shape=3)
    points.add_field("m")
    points.add_field("c", "int32")
    springs = simit.Set("springs", [points, points], endpoints=[[0, 1]])
    springs.add_field("k")
    springs.add_field("l0")
    return points, springs


def test_binding_errors_name_the_function_and_the_item():
    program = simit.compile(SPRINGS_SIM)
    points, springs = springs_sets()
    step = program.step
    step.bind(points=points, springs=springs)
    with pytest.raises(simit.Error, match=r"function 'step': extern '\w+' "
                                          r"is not bound"):
        step()
    flat, _ = springs_sets(x_shape=2)
    step.bind(points=flat)
    with pytest.raises(simit.Error, match=r"field 'points.x' holds float64 "
                                          r"components of shape \[2\]"):
        step.init()
    with pytest.raises(TypeError, match="'points' is an extern set"):
        step.bind(points=np.zeros(3))
    with pytest.raises(TypeError, match="'h' is an extern tensor; bind an "
                                        "array to it"):
        step.bind(h=points)
    with pytest.raises(simit.Error, match="uses no extern tensor named 'hh'"):
        step.bind(hh=0.01)
    with pytest.raises(TypeError, match="no exported function of the "
                                        "program uses 'hh'"):
        program.bind(hh=0.01)


def test_check_numerics_names_the_assembly():
    program = simit.compile(SPRINGS_SIM, check_numerics=True)
    points, springs = springs_sets()  # both points at the origin: l = 0
    externs = dict(h=0.01, viscous=2.0, stiffness=1e4, density=1e3,
                   radius=0.01, grav=[0.0, -9.81, 0.0], cgTol=1e-12,
                   cgMaxIters=50, runtimeSolve=0)
    program.bind(points=points, springs=springs, **externs)
    with pytest.raises(simit.NumericsError, match="produced nan") as info:
        program.step()
    assert info.value.file.endswith("springs.sim")
    assert info.value.line is not None


ZERO_LENGTH_SOLVE = """element P
  x : tensor[3](float);
  u : tensor[3](float);
end
element S
  k : float;
end
extern ps : set{P};
extern ss : set{S}(ps, ps);

const I = [1.0, 0.0, 0.0; 0.0, 1.0, 0.0; 0.0, 0.0, 1.0];

func spring(s : S, p : (P*2))
    -> (K : tensor[ps,ps](tensor[3,3](float)), f : tensor[ps](tensor[3](float)))
  d = p(1).x - p(0).x;
  K(p(0),p(0)) = s.k * I;
  K(p(1),p(1)) = s.k * I;
  f(p(0)) = d / norm(d);
  f(p(1)) = -d / norm(d);
end

export func step()
  K, f = map spring to ss reduce +;
  ps.u = K \\ f;
end
"""


def test_check_numerics_names_the_assembly_before_the_solve_it_broke():
    program = simit.compile(ZERO_LENGTH_SOLVE, name="zero.sim",
                            check_numerics=True)
    points = simit.Set("ps", size=2)
    points.add_field("x", shape=3)
    points.add_field("u", shape=3)
    springs = simit.Set("ss", [points, points], endpoints=[[0, 1]])
    springs.add_field("k")
    springs["k"][:] = 1.0
    program.bind(ps=points, ss=springs)
    # Both points at the origin: d / |d| = 0 / 0, and the solve of the nan
    # right-hand side fails; the assembly is named first, with the spring.
    with pytest.raises(simit.NumericsError,
                       match=r"map spring to ss \(zero.sim:23:\d+\) produced "
                             r"nan: f element \(ps 0\) component 0, "
                             r"assembled from ss 0; then solve \(zero.sim:"
                             r"24:\d+\): the right-hand side holds a NaN"):
        program.step()
    # Nothing of that failure is left behind for the next call.
    points["x"][1] = [1.0, 0.0, 0.0]
    program.step()
    np.testing.assert_allclose(points["u"], [[1, 0, 0], [-1, 0, 0]])


def test_a_negative_thread_count_is_refused():
    with pytest.raises(simit.Error, match="number of threads must be positive, not -1"):
        simit.compile(SPRINGS_SIM, threads=-1)
