"""simit.Set: fields as NumPy arrays over the set's own memory, edge sets
from index arrays, and the changes refused while views are alive."""

import numpy as np
import pytest

import simit

DOUBLE = """
element P
  a : float;
  b : float;
end
extern ps : set{P};

export func double()
  ps.b = 2.0 * ps.a;
end
"""


def test_numpy_writes_are_read_by_the_next_call_and_calls_write_the_views():
    program = simit.compile(DOUBLE)
    ps = simit.Set("ps", size=3)
    a = ps.add_field("a")
    b = ps.add_field("b")
    program.double.bind(ps=ps)
    a[:] = [1.0, 2.0, 3.0]
    program.double()
    # `b` was taken before the call: it shows the call's writes only if it
    # is the set's own array, not a copy.
    np.testing.assert_array_equal(b, [2.0, 4.0, 6.0])
    a[1] = 10.0  # written through the old view, read by the next call
    program.double()
    np.testing.assert_array_equal(b, [2.0, 20.0, 6.0])
    np.testing.assert_array_equal(ps["b"], b)
    assert np.shares_memory(ps["a"], a)


def test_fields_have_the_declared_dtype_and_block_shape():
    points = simit.Set("points", size=4)
    points.add_field("x", "float64", (3,))
    points.add_field("B", np.float32, (2, 2))
    points.add_field("c", "int32")
    points.add_field("fixed", bool)
    assert points["x"].shape == (4, 3) and points["x"].dtype == np.float64
    assert points["B"].shape == (4, 2, 2) and points["B"].dtype == np.float32
    assert points["c"].shape == (4,) and points["c"].dtype == np.int32
    assert points["fixed"].dtype == np.bool_
    assert set(points.fields) == {"x", "B", "c", "fixed"}
    assert points.fields["B"][1] == (2, 2)
    assert not points["x"].any()
    with pytest.raises(TypeError, match="float64, float32, int32 or bool"):
        points.add_field("bad", np.int64)


def test_assigning_a_new_field_takes_the_arrays_type_and_shape():
    points = simit.Set("points", size=2)
    points["x"] = np.array([[0.0, 1.0, 2.0], [3.0, 4.0, 5.0]])
    points["c"] = [1, 0]  # integers become int32
    assert points.fields["x"][1] == (3,)
    assert points["c"].dtype == np.int32
    points["x"] = 7.0  # an existing field is written in place
    np.testing.assert_array_equal(points["x"], np.full((2, 3), 7.0))
    with pytest.raises(ValueError, match="has 2 elements"):
        points["y"] = [1.0, 2.0, 3.0]


def test_edge_sets_from_index_arrays():
    points = simit.Set("points", size=4)
    springs = simit.Set("springs", [points, points],
                        endpoints=np.array([[0, 1], [1, 2], [2, 3]]))
    assert len(springs) == 3 and springs.cardinality == 2
    np.testing.assert_array_equal(springs.endpoints, [[0, 1], [1, 2], [2, 3]])
    assert springs.endpoint_sets == [points, points]
    assert springs.add_edges([[3, 0]]) == 3
    np.testing.assert_array_equal(springs.endpoints[-1], [3, 0])
    with pytest.raises(ValueError, match="row 1: .*endpoint 1 is 4, out of "
                                         "range for set 'points' of size 4"):
        springs.add_edges([[0, 1], [2, 4]])
    assert len(springs) == 4  # all or none
    with pytest.raises(ValueError, match=r"shape \(n, 2\)"):
        springs.add_edges([[0, 1, 2]])
    # Indices are whole numbers: 0.5 is not truncated to 0.
    with pytest.raises(ValueError, match="expected integer indices"):
        springs.add_edges([[0.5, 1.0]])
    with pytest.raises(ValueError, match="endpoint 1 is 10000000000, beyond "
                                         "32-bit indices"):
        springs.add_edges([[0, 10**10]])
    assert springs.add_edges([[1.0, 2.0]]) == 4
    np.testing.assert_array_equal(springs.endpoints[-1], [1, 2])
    with pytest.raises(ValueError):
        springs.endpoints[0, 0] = 1  # read-only


def test_adding_elements_is_refused_while_a_view_is_alive():
    points = simit.Set("points", size=2)
    x = points.add_field("x", shape=3)
    with pytest.raises(BufferError, match="1 live NumPy view"):
        points.add(100)
    del x
    assert points.add(100) == 2
    assert len(points) == 102 and points["x"].shape == (102, 3)


def test_remove_moves_the_last_element_into_the_slot():
    points = simit.Set("points", size=3)
    points["i"] = [0, 1, 2]
    points.remove(0)
    np.testing.assert_array_equal(points["i"], [2, 1])


def test_a_grid_over_points():
    points = simit.Set("points")
    grid = simit.Set.grid(points, [2, 3], "links")
    assert len(points) == 6 and grid.is_grid and grid.grid_dims == [2, 3]
    # Point (1, 2) = 5 links to (0, 2) = 2 along axis 0 (wrapping) and to
    # (1, 0) = 3 along axis 1.
    np.testing.assert_array_equal(grid.endpoints[5 * 2:5 * 2 + 2],
                                  [[5, 2], [5, 3]])


def test_an_edge_set_keeps_its_endpoint_sets_alive():
    springs = simit.Set("springs", [simit.Set("points", size=2)] * 2,
                        endpoints=[[0, 1]])
    (points, _) = springs.endpoint_sets
    assert len(points) == 2 and points.name == "points"


def test_values_that_do_not_fit_a_field_are_errors_not_wrapped():
    points = simit.Set("points", size=2)
    with pytest.raises(ValueError, match="expected int32 values .* found 3000000000"):
        points["n"] = np.array([3000000000, 1], dtype=np.int64)
    assert "n" not in points.fields
    with pytest.raises(TypeError, match="complex values cannot be held"):
        points["c"] = np.array([1 + 2j, 3 + 4j])
    points["n"] = [1, 2]
    with pytest.raises(ValueError, match="expected integers for int32"):
        points["n"] = [2.5, 1]
    assert points["n"].tolist() == [1, 2]


def extern_echo(name, type, **options):
    """A program whose f() returns extern `name` of Simit type `type`."""
    return simit.compile(f"extern {name} : {type};\n"
                         f"export func f() -> (r : {type})\n"
                         f"  r = {name};\nend\n", **options)


def test_an_int_extern_takes_integers_only():
    program = extern_echo("k", "int")
    with pytest.raises(ValueError, match="extern 'k': expected integers"):
        program.bind(k=2.5)
    with pytest.raises(ValueError, match="found 3e\\+09|found 3000000000"):
        program.bind(k=3e9)
    program.bind(k=7.0)
    assert program.f() == 7


def test_bool_and_float32_values_must_fit():
    program = extern_echo("b", "bool")
    with pytest.raises(ValueError, match="expected bool values \\(0 or 1\\)"):
        program.bind(b=0.5)
    with pytest.raises(ValueError, match="expected bool values"):
        program.bind(b=2)
    program.bind(b=1)
    assert program.f() is True
    single = extern_echo("x", "float", float32=True)
    with pytest.raises(ValueError, match="too large for float32"):
        single.bind(x=1e39)
