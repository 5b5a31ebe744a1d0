"""Pictures of a scene's frames: draws .vtu files (the surface of a tet
mesh, triangles, or a spring network) to PNG with matplotlib, coloured by a
point field (its magnitude for a vector field).

    python3 -m simit.render build/fem-dragon/dragon_*.vtu --field v \\
        --out build/pictures

writes build/pictures/dragon_0.png, ... All frames share the axes and the
colour scale, so a sequence of them shows the motion.
"""

import argparse
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the backend)
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import (Line3DCollection,  # noqa: E402
                                        Poly3DCollection)

from . import vtu  # noqa: E402

# The four faces of a tet (its vertices 0..3), each seen from outside for
# positively oriented tets.
_TET_FACES = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])


def boundary_faces(tets):
    """The faces of `tets` that belong to one tet only: the surface."""
    faces = tets[:, _TET_FACES].reshape(-1, 3)
    keys = np.sort(faces, axis=1)
    _, first, counts = np.unique(keys, axis=0, return_index=True,
                                 return_counts=True)
    return faces[first[counts == 1]]


def field_values(grid, field):
    """Per-point values of `field`: the field, or its norm when a vector."""
    if field not in grid.point_data:
        raise KeyError(f"no point field '{field}' (the file has: "
                       f"{', '.join(grid.point_data) or 'none'})")
    values = grid.point_data[field].astype(np.float64)
    return np.linalg.norm(values, axis=1) if values.ndim == 2 else values


def _frame_number(path):
    numbers = re.findall(r"\d+", os.path.basename(path))
    return int(numbers[-1]) if numbers else -1


def draw(grid, values, axes, norm, colormap, title):
    """Draws one grid on 3D `axes`, coloured by per-point `values`."""
    points = grid.points
    if 4 in grid.cells or 3 in grid.cells:
        faces = (boundary_faces(grid.cells[4]) if 4 in grid.cells
                 else grid.cells[3])
        colors = colormap(norm(values[faces].mean(axis=1)))
        axes.add_collection3d(Poly3DCollection(points[faces],
                                               facecolors=colors,
                                               edgecolors="none"))
    if 2 in grid.cells:
        lines = grid.cells[2]
        colors = colormap(norm(values[lines].mean(axis=1)))
        # Thick lines for a few springs, hairlines for thousands.
        width = min(2.0, max(0.3, 200.0 / len(lines)))
        axes.add_collection3d(Line3DCollection(points[lines], colors=colors,
                                               linewidths=width))
    if not ({2, 3, 4} & set(grid.cells)):
        axes.scatter(*points.T, c=colormap(norm(values)), s=2)
    axes.set_title(title)


def render(files, field, out_dir, *, view=(20, -60), size=(6.4, 4.8),
           dpi=100, colormap="viridis"):
    """Draws each .vtu of `files` to out_dir/<name>.png; returns the PNGs."""
    files = sorted(files, key=_frame_number)
    if not files:
        raise ValueError("no .vtu files to draw")
    grids = [vtu.read(path) for path in files]
    values = [field_values(grid, field) for grid in grids]
    all_points = np.concatenate([grid.points for grid in grids])
    low, high = all_points.min(axis=0), all_points.max(axis=0)
    centre, half = (low + high) / 2, (high - low).max() / 2 or 1.0
    norm = matplotlib.colors.Normalize(min(v.min() for v in values),
                                       max(v.max() for v in values))
    cmap = plt.get_cmap(colormap)
    os.makedirs(out_dir, exist_ok=True)
    written = []
    for path, grid, value in zip(files, grids, values):
        figure = plt.figure(figsize=size, dpi=dpi)
        axes = figure.add_subplot(projection="3d")
        name = os.path.splitext(os.path.basename(path))[0]
        draw(grid, value, axes, norm, cmap, name)
        for set_limits, c in zip((axes.set_xlim, axes.set_ylim,
                                  axes.set_zlim), centre):
            set_limits(c - half, c + half)
        axes.set_box_aspect((1, 1, 1))
        # The scenes fall along -y: show y upwards.
        axes.view_init(elev=view[0], azim=view[1], vertical_axis="y")
        figure.colorbar(matplotlib.cm.ScalarMappable(norm=norm, cmap=cmap),
                        ax=axes, shrink=0.7, label=f"|{field}|")
        png = os.path.join(out_dir, name + ".png")
        figure.savefig(png)
        plt.close(figure)
        written.append(png)
    return written


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog="python3 -m simit.render",
        description="Draws .vtu frames of a scene to PNG.")
    parser.add_argument("files", nargs="+", help=".vtu files")
    parser.add_argument("--field", required=True,
                        help="the point field that colours the drawing")
    parser.add_argument("--out", required=True, help="folder for the PNGs")
    parser.add_argument("--view", type=float, nargs=2, default=(20, -60),
                        metavar=("ELEVATION", "AZIMUTH"))
    parser.add_argument("--dpi", type=int, default=100)
    args = parser.parse_args(argv)
    try:
        for png in render(args.files, args.field, args.out,
                          view=tuple(args.view), dpi=args.dpi):
            print(png)
    except (KeyError, ValueError, OSError) as err:
        print(f"simit.render: {err}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
