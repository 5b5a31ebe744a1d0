"""examples/springs/springs.sim driven from Python, against the same step
computed with NumPy (a dense solve of bench/scenes.md's springs-bunny
system)."""

import numpy as np
import pytest

import simit

H, VISCOUS, STIFFNESS, DENSITY, RADIUS = 0.01, 2.0, 1e4, 1e3, 0.01
GRAVITY = np.array([0.0, -9.81, 0.0])


def numpy_masses(x, edges):
    m = np.zeros(len(x))
    for i, j in edges:
        half = 0.5 * DENSITY * np.pi * RADIUS**2 * np.linalg.norm(x[j] - x[i])
        m[i] += half
        m[j] += half
    return m


def numpy_step(x, v, m, c, edges, l0):
    """(MD + K) v' = fmg + fe solved exactly; x' = x + h v'."""
    n = len(x)
    A = np.zeros((3 * n, 3 * n))
    b = np.zeros(3 * n)
    eye = np.eye(3)
    block = lambda p: slice(3 * p, 3 * p + 3)  # noqa: E731
    for p in range(n):
        if c[p] > 0:
            A[block(p), block(p)] = eye
        else:
            A[block(p), block(p)] = (m[p] + H * VISCOUS) * eye
            b[block(p)] = m[p] * v[p] + H * m[p] * GRAVITY
    for s, (i, j) in enumerate(edges):
        d = x[j] - x[i]
        length = np.linalg.norm(d)
        U = d / length
        f = STIFFNESS * (length - l0[s])
        fe0 = H * f * U
        Kb = H * H * ((STIFFNESS - f / length) * np.outer(U, U) +
                      (f / length) * eye)
        free_i, free_j = c[i] <= 0, c[j] <= 0
        if free_i:
            b[block(i)] += fe0
            A[block(i), block(i)] += Kb
        if free_j:
            b[block(j)] -= fe0
            A[block(j), block(j)] += Kb
        if free_i and free_j:
            A[block(i), block(j)] -= Kb
            A[block(j), block(i)] -= Kb
    v_next = np.linalg.solve(A, b).reshape(n, 3)
    return x + H * v_next, v_next


@pytest.fixture
def net(springs_program):
    """A small spring net: a bent chain with cross braces, point 0 fixed."""
    rng = np.random.default_rng(7)
    x0 = np.array([[i * 0.1, 0.02 * i * i, 0.0] for i in range(6)])
    x0 += rng.uniform(-0.01, 0.01, x0.shape)
    edges = np.array([[0, 1], [1, 2], [2, 3], [3, 4], [4, 5], [0, 2], [1, 3],
                      [2, 4], [3, 5]])
    points = simit.Set("points", size=len(x0))
    points["x"] = x0
    points.add_field("v", shape=3)
    points.add_field("m")
    points["c"] = [1, 0, 0, 0, 0, 0]
    springs = simit.Set("springs", [points, points], endpoints=edges)
    springs.add_field("k")
    springs.add_field("l0")
    externs = dict(h=H, viscous=VISCOUS, stiffness=STIFFNESS, density=DENSITY,
                   radius=RADIUS, grav=GRAVITY, cgTol=1e-30, cgMaxIters=1000,
                   runtimeSolve=0)
    springs_program.bind(points=points, springs=springs, **externs)
    # The rest state is stretched so that springs pull from frame 1.
    springs_program.init()
    points["x"] *= 1.05
    return springs_program, points, springs, edges


def test_init_gives_each_point_half_of_its_springs_mass(net):
    _, points, springs, edges = net
    x = points["x"] / 1.05
    np.testing.assert_allclose(points["m"], numpy_masses(x, edges),
                               rtol=1e-14)
    np.testing.assert_allclose(springs["l0"],
                               np.linalg.norm(x[edges[:, 1]] - x[edges[:, 0]],
                                              axis=1), rtol=1e-14)


def test_steps_match_a_dense_numpy_solve(net):
    program, points, springs, edges = net
    x, v = points["x"].copy(), points["v"].copy()
    m, c, l0 = points["m"].copy(), points["c"].copy(), springs["l0"].copy()
    for _ in range(5):
        x, v = numpy_step(x, v, m, c, edges, l0)
        program.step()
        np.testing.assert_allclose(points["v"], v, rtol=0, atol=1e-10)
        np.testing.assert_allclose(points["x"], x, rtol=0, atol=1e-12)
    assert np.abs(v).max() > 1e-3  # the net moved
    np.testing.assert_array_equal(points["v"][0], [0.0, 0.0, 0.0])


def test_an_extern_array_is_shared_with_the_program(net):
    program, points, _, _ = net
    h = program.step["h"]
    assert h.shape == () and h.dtype == np.float64
    h[()] = 0.0  # no time passes: positions stay
    x = points["x"].copy()
    program.step()
    np.testing.assert_array_equal(points["x"], x)
    with pytest.raises(TypeError, match="would have to be copied"):
        program.step.bind(h=np.array(0.01, dtype=np.float32))


def steps_match_numpy(net, steps):
    """Runs `steps` steps of the program; after each, v equals the dense
    NumPy step's to 1e-10."""
    program, points, springs, edges = net
    x, v = points["x"].copy(), points["v"].copy()
    m, c, l0 = points["m"].copy(), points["c"].copy(), springs["l0"].copy()
    for _ in range(steps):
        x, v = numpy_step(x, v, m, c, edges, l0)
        program.step()
        np.testing.assert_allclose(points["v"], v, rtol=0, atol=1e-10)


def test_set_solver_chooses_how_the_step_solves(net):
    """runtimeSolve=1 solves with `A \\ b`; Cholesky through set_solver
    matches the dense NumPy solve, and solver_stats says what it did."""
    program, *_ = net
    program.bind(runtimeSolve=1)
    program.set_solver("cholesky")
    steps_match_numpy(net, 3)
    (stats,) = program.solver_stats()
    assert stats["methods"] == ["cholesky"]
    assert stats["solves"] == 3 and stats["factorisations"] == 3
    assert stats["analyses"] == 1
    assert stats["last_relative_residual"] < 1e-12


def test_pcg_cholesky_factorises_once_then_preconditions(net):
    """pcg-cholesky factorises the first frame's matrix and preconditions
    the later frames' CG with it; refactor_iters=1 makes every frame that
    needs more than one iteration factorise its own matrix."""
    program, *_ = net
    program.bind(runtimeSolve=1)
    program.set_solver("pcg-cholesky", tol=1e-12)
    steps_match_numpy(net, 3)
    (stats,) = program.solver_stats()
    assert stats["methods"] == ["pcg-cholesky"]
    assert stats["factorisations"] == 1
    assert stats["iterations"] > 3
    program.set_solver("pcg-cholesky", tol=1e-12, refactor_iters=1)
    program.step()
    (stats,) = program.solver_stats()
    assert stats["factorisations"] == 2
    with pytest.raises(ValueError, match="refactorisation threshold"):
        program.set_solver("pcg-cholesky", refactor_iters=0)


def test_a_strict_capped_solve_raises(net):
    program, *_ = net
    program.bind(runtimeSolve=1)
    program.set_solver("cg", max_iters=1, strict=True)
    with pytest.raises(simit.Error, match="iteration cap of 1"):
        program.step()


def test_bad_solver_settings_are_value_errors(net):
    program, *_ = net
    with pytest.raises(ValueError, match="not 'choleski'"):
        program.set_solver("choleski")
    with pytest.raises(ValueError, match="set_solver"):
        program.set_solver("cg", tol=2.0)
