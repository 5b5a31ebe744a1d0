"""The numerical stress suite's scenes and their independent reference.

  stress.py scene OUT [--option value ...]   writes OUT/bar.node, bar.ele,
      neo-hookean-solve.sim and scene.json
  stress.py check OUT CSV TOL [same options] runs the NumPy reference of the
      scene and compares every frame of CSV (columns frame,element,x_0..x_2)
  stress.py inverted OUT [same options]      prints the first frame and
      tetrahedron at which the reference's det F <= 0

The program is examples/fem/neo-hookean.sim with one textual change (so
that the suite runs the example's physics, not a copy of it): the Lame
parameters of each tetrahedron come from the scene (per-tet fields u and l)
instead of init's extern youngs and poisson. Its scene sets the extern
runtimeSolve to 1, so the step solves with `\` (the runtime's checked
solvers) instead of the conjugate gradient written in Simit, which stops at
its cap without telling anyone; with --example it runs the program as it
is, its own CG included.

The reference is a dense float64 NumPy implementation of the same linearly
implicit step: forces from the closed-form Neo-Hookean first Piola-Kirchhoff
stress, the stiffness matrix by complex-step differentiation of those forces
(exact to rounding, independent of the program's dPdF), numpy.linalg.solve.
"""
import argparse
import csv
import json
import os
import sys

# One thread: the arrays are tiny, and the test machine has two cores.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
import numpy as np  # noqa: E402 (after the thread setting)

PROGRAM = os.path.join(os.path.dirname(__file__), "..", "..", "..",
                       "examples", "fem", "neo-hookean.sim")
CHANGES = [
    ("  t.u = youngs / (2.0 * (1.0 + poisson));\n", ""),
    ("  t.l = youngs * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson));\n",
     ""),
]


def options(argv):
    p = argparse.ArgumentParser()
    p.add_argument("mode", choices=["scene", "check", "inverted"])
    p.add_argument("out")
    p.add_argument("rest", nargs="*")
    p.add_argument("--cubes", type=int, default=4)  # bar of n unit cubes
    p.add_argument("--h", type=float, default=0.01)
    p.add_argument("--frames", type=int, default=5)
    p.add_argument("--youngs", type=float, default=1e5)
    # Young's modulus grows geometrically along the bar by this factor.
    p.add_argument("--ratio", type=float, default=1.0)
    p.add_argument("--poisson", type=float, default=0.3)
    p.add_argument("--density", type=float, default=1000.0)
    # Initial velocity of the free end's vertices (the tip at x = n).
    p.add_argument("--tip-velocity", type=float, nargs=3, default=[0, 0, 0])
    # A degenerate (flat) tetrahedron added over the tip face.
    p.add_argument("--flat-tet", action="store_true")
    # The scene runs the unchanged example (its conjugate gradient written
    # in Simit, one Young's modulus): no --ratio.
    p.add_argument("--example", action="store_true")
    p.add_argument("--cg-max-iters", type=int, default=1000)
    return p.parse_args(argv)


def bar(n, flat):
    """Points and tets of n unit cubes along x, six tets per cube (Kuhn),
    every tet positively oriented."""
    pts = np.array([(i, j, k) for i in range(n + 1) for j in (0, 1)
                    for k in (0, 1)], dtype=float)
    index = {tuple(p.astype(int)): a for a, p in enumerate(pts)}
    perms = [(0, 1, 2), (0, 2, 1), (1, 0, 2), (1, 2, 0), (2, 0, 1), (2, 1, 0)]
    tets = []
    for i in range(n):
        for perm in perms:
            c = [i, 0, 0]
            tet = [index[tuple(c)]]
            for axis in perm:
                c[axis] += 1
                tet.append(index[tuple(c)])
            if signed_volumes(pts, [tet])[0] < 0:
                tet[0], tet[1] = tet[1], tet[0]
            tets.append(tet)
    if flat:
        # The tip face's four corners lie in the plane x = n: volume 0.
        tets.append([index[(n, 0, 0)], index[(n, 1, 0)], index[(n, 0, 1)],
                     index[(n, 1, 1)]])
    return pts, np.array(tets)


def signed_volumes(pts, tets):
    t = np.asarray(tets)
    d = pts[t[:, :3]] - pts[t[:, 3:4]]
    return np.linalg.det(np.transpose(d, (0, 2, 1))) / 6.0


def materials(o, pts, tets):
    """Per-tet mu and lambda: E grows by `ratio` from the fixed to the free
    end, geometrically in the centroid's x."""
    cx = pts[tets].mean(axis=1)[:, 0] / o.cubes
    youngs = o.youngs * o.ratio ** cx
    nu = o.poisson
    mu = youngs / (2.0 * (1.0 + nu))
    lam = youngs * nu / ((1.0 + nu) * (1.0 - 2.0 * nu))
    return mu, lam


def write_scene(o):
    os.makedirs(o.out, exist_ok=True)
    pts, tets = bar(o.cubes, o.flat_tet)
    with open(os.path.join(o.out, "bar.node"), "w") as f:
        f.write(f"{len(pts)} 3 0 0\n")
        for a, p in enumerate(pts):
            f.write(f"{a} {p[0]:.17g} {p[1]:.17g} {p[2]:.17g}\n")
    with open(os.path.join(o.out, "bar.ele"), "w") as f:
        f.write(f"{len(tets)} 4 0\n")
        for e, t in enumerate(tets):
            f.write(f"{e} {t[0]} {t[1]} {t[2]} {t[3]}\n")
    with open(PROGRAM) as f:
        text = f.read()
    for old, new in CHANGES:
        if text.count(old) != 1:
            sys.exit(f"stress.py: {PROGRAM} no longer holds {old!r} once")
        text = text.replace(old, new)
    with open(os.path.join(o.out, "neo-hookean-solve.sim"), "w") as f:
        f.write(text)
    # The program's own CG runs only with --example (runtimeSolve 0), but
    # the step uses its externs in either branch.
    externs = {"h": o.h, "density": o.density, "grav": [0, -10, 0],
               "runtimeSolve": {"type": "int32",
                                "value": 0 if o.example else 1},
               "cgTol": 1e-30, "cgMaxIters": {
                   "type": "int32", "value": o.cg_max_iters}}
    if not o.example:
        mu, lam = materials(o, pts, tets)
        tet_fields = {"u": {"values": mu.tolist()},
                      "l": {"values": lam.tolist()}}
    else:
        assert o.ratio == 1, "the example has one Young's modulus"
        tet_fields = {}
        externs.update({"youngs": o.youngs, "poisson": o.poisson})
    tip = f"x > {o.cubes - 1e-9}"
    scene = {
        "program": (os.path.abspath(PROGRAM) if o.example
                    else "neo-hookean-solve.sim"),
        "meshes": {"bar": "bar.node"},
        "sets": {
            "verts": {"mesh": "bar", "fields": {
                "x": {"coordinates": "mesh"},
                "c": {"type": "int32", "expr": "x < 1e-9"},
                "v": {"if": tip, "then": o.tip_velocity, "else": [0, 0, 0]},
            }},
            "tets": {"mesh": "bar", "elements": "tets", "endpoints": "verts",
                     "fields": tet_fields},
        },
        "externs": externs,
        "init": "init",
        "step": "step",
        "frames": o.frames,
        "outputs": [{"format": "csv", "path": "x.csv", "set": "verts",
                     "fields": ["x"]}],
    }
    with open(os.path.join(o.out, "scene.json"), "w") as f:
        json.dump(scene, f, indent=1)


def forces(x, rest_inv, vol, mu, lam, tets, fixed):
    """Elastic forces of every tet on its vertices, for a batch of position
    arrays x[..., verts, 3] (complex for the complex step)."""
    d = x[..., tets[:, :3], :] - x[..., tets[:, 3:4], :]  # [..., T, 3, 3]
    ds = np.swapaxes(d, -1, -2)  # columns x_i - x_3
    F = ds @ rest_inv
    # F^-T = cofactor(F) / det F; the cofactor's columns are cross products
    # of F's columns (numpy's batched inv is slow on complex 3x3 blocks).
    a, b, c = F[..., :, 0], F[..., :, 1], F[..., :, 2]
    cof = np.stack([np.cross(b, c), np.cross(c, a), np.cross(a, b)], axis=-1)
    J = (a * cof[..., :, 0]).sum(axis=-1)
    Finv_t = cof / J[..., None, None]
    P = (mu[:, None, None] * (F - Finv_t)
         + (lam * np.log(J))[..., None, None] * Finv_t)
    H = -vol[:, None, None] * P @ np.swapaxes(rest_inv, -1, -2)
    per_vertex = np.concatenate(
        [np.swapaxes(H, -1, -2), -H.sum(axis=-1)[..., None, :]], axis=-2)
    # Sum into the vertices: incidence[v, 4 t + k] = 1 when tet t's k-th
    # vertex is v.
    incidence = np.zeros((x.shape[-2], 4 * len(tets)))
    incidence[tets.reshape(-1), np.arange(4 * len(tets))] = 1
    f = incidence @ per_vertex.reshape(per_vertex.shape[:-3] + (-1, 3))
    f[..., fixed, :] = 0
    return f


def simulate(o, conditions=None):
    """Yields the positions after init (frame 0) and after every step, or
    raises FloatingPointError naming the frame and first tet with det F <= 0.
    Appends the condition number of each frame's A to `conditions`."""
    pts, tets = bar(o.cubes, o.flat_tet)
    mu, lam = materials(o, pts, tets)
    nv = len(pts)
    fixed = pts[:, 0] < 1e-9
    dm = np.swapaxes(pts[tets[:, :3]] - pts[tets[:, 3:4]], -1, -2)
    rest_inv = np.linalg.inv(dm)
    vol = np.abs(np.linalg.det(dm)) / 6.0
    m = np.zeros(nv)
    for a in range(4):
        np.add.at(m, tets[:, a], 0.25 * o.density * vol)
    g = np.array([0.0, -10.0, 0.0])
    fg = np.where(fixed[:, None], 0.0, m[:, None] * g)
    x = pts.copy()
    v = np.zeros_like(x)
    v[pts[:, 0] > o.cubes - 1e-9] = o.tip_velocity
    yield x
    free = ~np.repeat(fixed, 3)
    eps = 1e-30
    for frame in range(1, o.frames + 1):
        J = np.linalg.det(np.swapaxes(x[tets[:, :3]] - x[tets[:, 3:4]], -1, -2)
                          @ rest_inv)
        if (J <= 0).any():
            raise FloatingPointError(frame, int(np.argmax(J <= 0)))
        f = forces(x, rest_inv, vol, mu, lam, tets, fixed).reshape(-1)
        # K[:, j] = d f / d x_j by the complex step, all j in one batch.
        probe = np.broadcast_to(x, (3 * nv, nv, 3)).astype(complex)
        probe = probe.reshape(3 * nv, 3 * nv).copy()
        probe[np.arange(3 * nv), np.arange(3 * nv)] += 1j * eps
        K = forces(probe.reshape(3 * nv, nv, 3), rest_inv, vol, mu, lam, tets,
                   fixed).reshape(3 * nv, 3 * nv).imag.T / eps
        K[~free, :] = 0
        K[:, ~free] = 0
        M = np.diag(np.repeat(m, 3))
        A = M - o.h * o.h * K
        b = M @ v.reshape(-1) + o.h * (f + fg.reshape(-1))
        if conditions is not None:
            conditions.append(np.linalg.cond(A))
        v = np.linalg.solve(A, b).reshape(nv, 3)
        x = x + o.h * v
        yield x


def read_frames(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    assert rows[0] == ["frame", "element", "x_0", "x_1", "x_2"], rows[0]
    frames = {}
    for row in rows[1:]:
        frames.setdefault(int(row[0]), []).append([float(v) for v in row[2:]])
    return [np.array(frames[k]) for k in sorted(frames)]


def check(o, path, tol):
    """The largest error over all frames, relative to the largest
    displacement of the reference: positions are O(n) while displacements
    can be 1e-7 of that (h = 1e-4), and it is the displacement that the
    simulation computes."""
    run = read_frames(path)
    conditions = []
    ref = list(simulate(o, conditions))
    if len(run) != len(ref):
        sys.exit(f"{path}: {len(run)} frames, the reference has {len(ref)}")
    scale = max(np.abs(r - ref[0]).max() for r in ref)
    worst = max(np.abs(a - r).max() for a, r in zip(run, ref))
    error = worst / scale
    verdict = "within" if error <= tol else "ABOVE"
    print(f"{len(run) - 1} frames, largest displacement {scale:.3g}, "
          f"relative error {error:.2e} {verdict} tolerance {tol:g} "
          f"(cond(A) <= {max(conditions):.2g})")
    if error > tol:
        sys.exit(1)


def main():
    o = options(sys.argv[1:])
    if o.mode == "scene":
        write_scene(o)
    elif o.mode == "check":
        check(o, o.rest[0], float(o.rest[1]))
    else:
        try:
            for _ in simulate(o):
                pass
        except FloatingPointError as e:
            print(f"reference inverts tet {e.args[1]} in frame {e.args[0]}")
            return
        sys.exit("the reference never inverts a tet")


if __name__ == "__main__":
    main()
