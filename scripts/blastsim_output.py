"""Readers of a blastsim run's output folder shared by the plotting scripts: CSV series as numpy columns,
ParaView collections (.pvd) and VTK unstructured grids (.vtu). Imported by plot-single-hole.py and
plot-analysis.py (they put this folder on sys.path); needs numpy and python3-vtk9.
"""
import csv
import os
import xml.etree.ElementTree as ET

import numpy as np
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader


def read_csv(path):
    """Columns of a CSV file keyed by header name: numpy arrays, or lists of strings for a column that is not
    numeric (a probe's name). None if the file is missing or has no rows."""
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
            cols[name] = np.array([float(v) for v in values])
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
