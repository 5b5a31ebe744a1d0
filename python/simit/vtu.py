"""Reading the ASCII .vtu files simit-run and simit.Scene write (VTK XML
UnstructuredGrid, lib/Runtime/VTK.cpp) into NumPy arrays."""

import xml.etree.ElementTree as ElementTree

import numpy as np

# VTK cell type -> number of points: vertex, line, triangle, tetra.
CELL_POINTS = {1: 1, 3: 2, 5: 3, 10: 4}
_DTYPES = {"Float64": np.float64, "Float32": np.float32, "Int32": np.int32,
           "Int64": np.int64, "UInt8": np.uint8}


class Grid:
    """A .vtu file's points (n, 3), its cells grouped by point count
    ({2: (m, 2) array, 4: (m, 4) array, ...}), and its point and cell data
    ({name: array of shape (n,) or (n, components)})."""

    def __init__(self, points, cells, point_data, cell_data):
        self.points = points
        self.cells = cells
        self.point_data = point_data
        self.cell_data = cell_data


def _array(element):
    values = np.array(element.text.split(), dtype=_DTYPES[element.get("type")])
    components = int(element.get("NumberOfComponents", "1"))
    return values.reshape(-1, components) if components > 1 else values


def read(path):
    """The Grid of the .vtu file at `path`."""
    piece = ElementTree.parse(path).getroot().find("UnstructuredGrid/Piece")
    points = _array(piece.find("Points/DataArray")).reshape(-1, 3)
    cell_arrays = {a.get("Name"): _array(a)
                   for a in piece.findall("Cells/DataArray")}
    connectivity = cell_arrays["connectivity"]
    offsets = cell_arrays["offsets"]
    types = cell_arrays["types"]
    starts = np.concatenate(([0], offsets[:-1]))
    cells = {}
    for cell_type in np.unique(types):
        count = CELL_POINTS[int(cell_type)]
        chosen = starts[types == cell_type]
        cells[count] = connectivity[chosen[:, None] + np.arange(count)]
    point_data = {a.get("Name"): _array(a)
                  for a in piece.findall("PointData/DataArray")}
    cell_data = {a.get("Name"): _array(a)
                 for a in piece.findall("CellData/DataArray")}
    return Grid(points, cells, point_data, cell_data)
