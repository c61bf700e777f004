"""Readers of a blastsim run's output folder shared by the plotting scripts: CSV series as numpy columns,
ParaView collections (.pvd), VTK unstructured grids (.vtu), the gas image (.vti), the rock's triangles and its
cracks. Imported by plot-single-hole.py, plot-bench.py and plot-analysis.py (they put this folder on sys.path); needs numpy and python3-vtk9.
"""
import csv
import os
import xml.etree.ElementTree as ET

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLImageDataReader, vtkXMLUnstructuredGridReader


def read_csv(path):
    """Columns of a CSV file keyed by header name: numpy arrays (an empty field, a quantity that could not be
    computed, reads as NaN), or lists of strings for a column that is not numeric (a probe's name). None if the
    file is missing or has no rows."""
    if not os.path.exists(path):
        return None
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if len(rows) < 2:
        return None
    cols = {}
    for k, name in enumerate(rows[0]):
        values = [r[k] for r in rows[1:]]
        try:
            cols[name] = np.array([float(v) if v != "" else np.nan for v in values])
        except ValueError:
            cols[name] = values
    return cols


def pvd_entries(path):
    """(time, file) pairs of a ParaView collection ([] if it is missing)."""
    if not os.path.exists(path):
        return []
    return [(float(d.get("timestep")), d.get("file")) for d in ET.parse(path).getroot().iter("DataSet")]


def read_grid(path):
    """A .vtu file as a vtkUnstructuredGrid."""
    r = vtkXMLUnstructuredGridReader()
    r.SetFileName(path)
    r.Update()
    return r.GetOutput()


def read_gas(path):
    """A gas snapshot (.vti): extent, pressure, speed and the active mask as 2-D arrays (rows along y)."""
    r = vtkXMLImageDataReader()
    r.SetFileName(path)
    r.Update()
    img = r.GetOutput()
    nx, ny, _ = img.GetDimensions()
    nx, ny = nx - 1, ny - 1
    x0, y0, _ = img.GetOrigin()
    dx, dy, _ = img.GetSpacing()
    cd = img.GetCellData()
    field = lambda name: vtk_to_numpy(cd.GetArray(name)).reshape(ny, nx, -1).squeeze()  # noqa: E731
    vel = field("velocity")
    return {
        "extent": (x0, x0 + nx * dx, y0, y0 + ny * dy),
        "pressure": field("pressure"),
        "speed": np.hypot(vel[..., 0], vel[..., 1]),
        "active": field("active"),
    }


def read_rock(path):
    """A rock snapshot (.vtu): its triangles (n x 3 x 2 corners) and their most compressive principal stress."""
    g = read_grid(path)
    pts = vtk_to_numpy(g.GetPoints().GetData())[:, :2]
    tris = pts.reshape(-1, 3, 2)  # FDEM: three own nodes per triangle, in order
    return tris, vtk_to_numpy(g.GetCellData().GetArray("principal_min"))


def read_cracks(path):
    """A joints snapshot (.vtu): the broken joints as segments (n x 2 x 2)."""
    g = read_grid(path)
    pts = vtk_to_numpy(g.GetPoints().GetData())[:, :2].reshape(-1, 2, 2)
    broken = vtk_to_numpy(g.GetCellData().GetArray("broken")).astype(bool)
    return pts[broken]
