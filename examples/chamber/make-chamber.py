#!/usr/bin/python3
"""Generates the pressure chamber's mesh: a thick hollow box.

A structured grid of nx x ny x nz cubic cells, of which those deeper than
`wall` cells from the outside are removed (the cavity), the rest split into
six tetrahedra each (the Kuhn split along the cell's main diagonal, the
same in every cell, so neighbouring cells share their face diagonals).
Writes TetGen files into OUT:

  chamber.node  the grid points that belong to a wall cell (0-based)
  chamber.ele   the tetrahedra, positively oriented
  chamber.face  the cavity's surface only: two triangles per cell face, each
                oriented with its normal out of the cavity (into the wall)
  chamber.json  the scene examples/chamber/chamber.json with its program
                and mesh paths pointing at this folder (unless --no-scene)

The box is centred on the origin, so the origin lies inside the cavity.
--unknowns N picks the grid (a cube-like box with a one-cell wall)
whose Newton system has nearest to N unknowns: 3 per vertex, the fixed
ones (the outer bottom face) included, as the program keeps them as
identity rows.
"""

import argparse
import itertools
import json
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))


def grid_index(nx, ny, nz):
    """Index of grid point (i, j, k) in the full (nx+1)(ny+1)(nz+1) grid."""
    return lambda i, j, k: (i * (ny + 1) + j) * (nz + 1) + k


def wall_cells(nx, ny, nz, wall):
    cells = np.array(list(itertools.product(range(nx), range(ny), range(nz))))
    lo = np.array([wall] * 3)
    hi = np.array([nx - wall, ny - wall, nz - wall])
    in_cavity = np.all((cells >= lo) & (cells < hi), axis=1)
    return cells[~in_cavity]


def kuhn_tets(cells):
    """The six tets of each cell: 000 -> e_a -> e_a + e_b -> 111."""
    tets = []
    for perm in itertools.permutations(range(3)):
        corners = [np.zeros(3, dtype=int)]
        for axis in perm:
            step = corners[-1].copy()
            step[axis] = 1
            corners.append(step)
        tets.append(np.stack([cells + c for c in corners], axis=1))
    return np.concatenate(tets)  # (cells * 6, 4, 3) grid coordinates


def cavity_triangles(nx, ny, nz, wall):
    """The cavity's faces as triangles of grid coordinates, split along the
    diagonal the Kuhn tets use (from the face's lowest corner)."""
    size = (nx, ny, nz)
    tris = []
    for axis in range(3):
        b, c = [a for a in range(3) if a != axis]
        for plane in (wall, size[axis] - wall):
            for s in range(wall, size[b] - wall):
                for t in range(wall, size[c] - wall):
                    def point(db, dc):
                        p = [0, 0, 0]
                        p[axis], p[b], p[c] = plane, s + db, t + dc
                        return p
                    tris.append([point(0, 0), point(1, 0), point(1, 1)])
                    tris.append([point(0, 0), point(1, 1), point(0, 1)])
    return np.array(tris)


def generate(nx, ny, nz, wall, cell):
    if min(nx, ny, nz) < 2 * wall + 1 or wall < 1:
        sys.exit("make-chamber: every side needs at least 2*wall+1 cells and "
                 "wall >= 1")
    index = grid_index(nx, ny, nz)
    tets = kuhn_tets(wall_cells(nx, ny, nz, wall))
    tris = cavity_triangles(nx, ny, nz, wall)
    flat = lambda g: index(g[..., 0], g[..., 1], g[..., 2])
    tet_ids, tri_ids = flat(tets), flat(tris)
    used = np.unique(tet_ids)
    renumber = np.full((nx + 1) * (ny + 1) * (nz + 1), -1)
    renumber[used] = np.arange(len(used))
    ijk = np.stack(np.unravel_index(used, (nx + 1, ny + 1, nz + 1)), axis=1)
    points = (ijk - np.array([nx, ny, nz]) / 2.0) * cell
    tet_ids, tri_ids = renumber[tet_ids], renumber[tri_ids]
    assert (tri_ids >= 0).all()

    # Orient tets positively and triangles away from the cavity's centre
    # (the origin), which makes sum det[a b c] / 6 the cavity's volume.
    def det(p):
        return np.einsum("ij,ij->i", p[:, 0], np.cross(p[:, 1], p[:, 2]))
    t = points[tet_ids]
    inverted = det(t[:, 1:] - t[:, :1]) < 0
    tet_ids[inverted] = tet_ids[inverted][:, [0, 2, 1, 3]]
    f = points[tri_ids]
    normal = np.cross(f[:, 1] - f[:, 0], f[:, 2] - f[:, 0])
    inward = np.einsum("ij,ij->i", normal, f.mean(axis=1)) < 0
    tri_ids[inward] = tri_ids[inward][:, [0, 2, 1]]
    volume = det(points[tri_ids]).sum() / 6.0
    inner = [(n - 2 * wall) * cell for n in (nx, ny, nz)]
    assert abs(volume - np.prod(inner)) < 1e-9 * np.prod(inner), volume
    return points, tet_ids, tri_ids


def vertex_count(nx, ny, nz, wall):
    points = (nx + 1) * (ny + 1) * (nz + 1)
    return points - (nx - 2 * wall - 1) * (ny - 2 * wall - 1) * \
        (nz - 2 * wall - 1)


def fixed_count(nx, ny, nz):
    return (nx + 1) * (ny + 1)


def grid_for(unknowns):
    """The box with a one-cell wall and sides within two cells of each
    other with nearest to `unknowns` system unknowns."""
    best = None
    for nx in range(3, 200):
        for ny in range(nx, nx + 3):
            for nz in range(ny, nx + 3):
                key = abs(3 * vertex_count(nx, ny, nz, 1) - unknowns)
                if best is None or key < best[0]:
                    best = (key, (nx, ny, nz, 1))
        if 3 * vertex_count(nx, nx, nx, 1) > 2 * unknowns:
            break
    return best[1]


def write(out, points, tets, tris):
    os.makedirs(out, exist_ok=True)
    base = os.path.join(out, "chamber")
    with open(base + ".node", "w") as f:
        f.write(f"{len(points)} 3 0 0\n")
        for i, p in enumerate(points):
            f.write(f"{i} {p[0]:.17g} {p[1]:.17g} {p[2]:.17g}\n")
    for ext, cells in ((".ele", tets), (".face", tris)):
        with open(base + ext, "w") as f:
            f.write(f"{len(cells)} {cells.shape[1]} 0\n" if ext == ".ele"
                    else f"{len(cells)} 0\n")
            for i, c in enumerate(cells):
                f.write(f"{i} " + " ".join(map(str, c)) + "\n")


def default_pressure(template_p0, cells, wall, cell):
    """The scene's p0 up to a cavity of 4 cells; for larger boxes scaled
    by wall / cavity side, which keeps the membrane stress p R / t of the
    walls, so that large boxes inflate as much as small ones."""
    ratio = wall * cell / ((max(cells) - 2 * wall) * cell)
    return template_p0 * min(1.0, 4 * ratio)


def write_scene(out, frames, pressure, cells, wall, cell):
    with open(os.path.join(HERE, "chamber.json")) as f:
        scene = json.load(f)
    scene["program"] = os.path.join(HERE, "chamber.sim")
    scene["meshes"]["chamber"] = "chamber.node"
    externs = scene["externs"]
    externs["p0"] = pressure if pressure is not None else \
        default_pressure(externs["p0"], cells, wall, cell)
    if frames is not None:
        scene["frames"] = frames
    with open(os.path.join(out, "chamber.json"), "w") as f:
        json.dump(scene, f, indent=2)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", default="build/chamber",
                        help="output folder (default build/chamber)")
    parser.add_argument("--cells", type=int, nargs=3, metavar=("NX", "NY", "NZ"),
                        help="cells along x, y, z (default 6 6 6)")
    parser.add_argument("--wall", type=int, default=1,
                        help="wall thickness in cells (default 1)")
    parser.add_argument("--unknowns", type=int,
                        help="choose cells and wall for about this many "
                        "free unknowns (instead of --cells/--wall)")
    parser.add_argument("--cell", type=float, default=0.1,
                        help="cell edge length (default 0.1)")
    parser.add_argument("--pressure", type=float,
                        help="the scene's p0 (default: that of chamber.json "
                        "for cavities up to 4 cells wide, scaled by 4 cells "
                        "/ cavity width beyond)")
    parser.add_argument("--frames", type=int,
                        help="the scene's frame count (Newton iterations)")
    parser.add_argument("--no-scene", action="store_true",
                        help="write only the mesh")
    args = parser.parse_args()
    if args.unknowns is not None:
        nx, ny, nz, wall = grid_for(args.unknowns)
    else:
        nx, ny, nz = args.cells or (6, 6, 6)
        wall = args.wall
    points, tets, tris = generate(nx, ny, nz, wall, args.cell)
    write(args.out, points, tets, tris)
    if not args.no_scene:
        write_scene(args.out, args.frames, args.pressure, (nx, ny, nz), wall,
                    args.cell)
    print(f"chamber: cells {nx}x{ny}x{nz}, wall {wall}: {len(points)} "
          f"vertices, {len(tets)} tets, {len(tris)} cavity triangles, "
          f"{3 * len(points)} unknowns ({3 * fixed_count(nx, ny, nz)} of them "
          f"fixed) -> {args.out}")


if __name__ == "__main__":
    main()
