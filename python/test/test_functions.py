"""Functions with parameters and results, called from Python."""

import numpy as np
import pytest

import simit

PARAMETERS = """
export func scale(a : float, v : tensor[3](float)) -> (r : tensor[3](float))
  r = a * v;
end

export func both(n : int, v : tensor[2](float)) -> (twice : int, s : float)
  twice = 2 * n;
  s = v(0) + v(1);
end
"""


def test_parameters_in_and_results_out():
    program = simit.compile(PARAMETERS)
    v = np.array([1.0, -2.0, 0.5])
    np.testing.assert_array_equal(program.scale(3.0, v), 3.0 * v)
    assert program.scale.num_parameters == 2
    assert program.both(21, [0.25, 0.5]) == (42, 0.75)


EXTERN_VECTOR = """
element P a : float; end
extern ps : set{P};
extern u : vector[ps](vector[2](float));
export func step()
  u = 2.0 * u;
end
"""


def test_an_extern_vector_over_a_set_is_bound_in_place():
    program = simit.compile(EXTERN_VECTOR)
    ps = simit.Set("ps", size=3)
    ps.add_field("a")
    u = np.arange(6.0).reshape(3, 2)
    program.bind(ps=ps, u=u)
    # -1: one block per element of the set bound.
    assert program.step.externs == {"u": (np.dtype("float64"), (-1, 2))}
    program.step()
    np.testing.assert_array_equal(u, 2.0 * np.arange(6.0).reshape(3, 2))
    program.step.bind(u=np.zeros((2, 2)))
    with pytest.raises(simit.Error, match=r"expects float64 of shape \[3, 2\]"):
        program.step()


def test_a_matrix_parameter_takes_its_declared_shape_or_flat():
    program = simit.compile(
        "export func m(a : matrix[2,3](float)) -> (r : float)\n"
        "  r = a(1,0);\nend\n")
    assert program.m(np.arange(6.0).reshape(2, 3)) == 3.0
    assert program.m(np.arange(6.0)) == 3.0  # flat, row-major
    # As many numbers, the other shape: refused, not read as 2x3.
    with pytest.raises(simit.Error, match=r"parameter 0 is bound to float64 "
                       r"of shape \[3, 2\], but the program declares shape "
                       r"\[2, 3\]"):
        program.m(np.arange(6.0).reshape(3, 2))


def test_a_matrix_result_has_its_declared_shape():
    program = simit.compile(
        "export func m(a : float) -> (r : matrix[2,3](float), "
        "c : matrix[2,2](complex), v : vector[3](float))\n"
        "  r = a * [1.0, 2.0, 3.0; 4.0, 5.0, 6.0];\n"
        "  c = [<1.0, 2.0>, <0.0, 0.0>; <0.0, -1.0>, <3.0, 0.0>];\n"
        "  v = [7.0, 8.0, 9.0]';\nend\n")
    r, c, v = program.m(2.0)
    np.testing.assert_array_equal(r, 2.0 * np.arange(1.0, 7.0).reshape(2, 3))
    np.testing.assert_array_equal(
        c, np.array([[1 + 2j, 0], [-1j, 3]], dtype=np.complex128))
    np.testing.assert_array_equal(v, [7.0, 8.0, 9.0])


def test_a_complex_scalar_parameter_takes_a_python_complex():
    program = simit.compile("export func sq(c : complex) -> (d : complex)\n"
                            "  d = c * c;\nend\n")
    assert program.sq(1 + 2j) == -3 + 4j
    assert program.sq(np.complex128(2j)) == -4


def test_a_vector_over_a_set_parameter_has_a_block_per_element():
    program = simit.compile("element V\n  x : float;\nend\n"
                            "extern verts : set{V};\n"
                            "export func scale(s : vector[verts](float))\n"
                            "  verts.x = verts.x .* s;\nend\n")
    verts = simit.Set("verts", size=3)
    verts["x"] = np.array([1.0, 2.0, 3.0])
    program.bind(verts=verts)
    program.scale(np.array([2.0, 3.0, 4.0]))
    np.testing.assert_array_equal(verts["x"], [2.0, 6.0, 12.0])
    with pytest.raises(simit.Error, match=r"parameter 0 is bound to float64 "
                       r"of shape \[2\], but the program expects float64 of "
                       r"shape \[3\]"):
        program.scale(np.array([2.0, 3.0]))
