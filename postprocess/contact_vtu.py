#!/usr/bin/python3
"""Reading dualcontact's VTU output with VTK's Python module.

Run with /usr/bin/python3: Debian's python3-vtk9 (pulled in by libvtk9-dev,
which the build needs; scripts/setup installs both) and python3-numpy.

    import contact_vtu
    grid = contact_vtu.read_grid("output/contact_1.vtu")   # or a .pvtu / .pvd
    points, fields = contact_vtu.read_vtu("output/contact_1.vtu")
    points, fields = contact_vtu.read_contact_nodes("output/contact_1.pvtu")
    force = contact_vtu.integrate(grid)["pressure_Pa"]

A contact-surface file (contact_N.vtu, or contact_N.pvtu with one piece per
process under MPI) holds the slave faces as line (2D) or quadrilateral (3D)
cells.  Its points are the contact nodes and, with status -1, points that
are no contact nodes (hanging nodes of adaptive meshes, nodes beyond the
search distance); read_contact_nodes() returns the contact nodes only, each
once (the pieces of a .pvtu share the points on their borders).
"""
import os
import sys
import xml.etree.ElementTree as ET

try:
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkFiltersParallel import vtkIntegrateAttributes
    from vtkmodules.vtkIOXML import (vtkXMLPUnstructuredGridReader,
                                     vtkXMLUnstructuredGridReader)
except ImportError as error:
    MISSING = ("VTK's Python module is missing (%s): install the Debian "
               "package python3-vtk9 (scripts/setup does) and run with "
               "/usr/bin/python3" % error)
else:
    MISSING = None

import numpy

NO_CONTACT_NODE = -1


def require_vtk():
    """Exit with a clear message when VTK's Python module is missing."""
    if MISSING:
        sys.exit(MISSING)


def read_grid(path):
    """The vtkUnstructuredGrid of a .vtu, a .pvtu (its pieces appended) or a
    .pvd (its last data set: a .vtu or .pvtu)."""
    require_vtk()
    if not os.path.isfile(path):
        raise FileNotFoundError(f"{path}: no such file")
    if path.endswith(".pvd"):
        sets = ET.parse(path).getroot().findall("Collection/DataSet")
        if not sets:
            raise ValueError(f"{path}: no data set")
        return read_grid(os.path.join(os.path.dirname(path),
                                      sets[-1].get("file")))
    reader = (vtkXMLPUnstructuredGridReader() if path.endswith(".pvtu")
              else vtkXMLUnstructuredGridReader())
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    if grid is None or (grid.GetNumberOfPoints() == 0
                        and os.path.getsize(path) == 0):
        raise ValueError(f"{path}: VTK could not read it")
    return grid


def point_fields(grid):
    """{name: numpy array} of the point data: (n,) for scalars, (n, k) for
    fields of k components."""
    data = grid.GetPointData()
    return {data.GetArrayName(i): vtk_to_numpy(data.GetArray(i)).copy()
            for i in range(data.GetNumberOfArrays())}


def points_of(grid):
    """The points as an (n, 3) numpy array."""
    if grid.GetNumberOfPoints() == 0:
        return numpy.zeros((0, 3))
    return vtk_to_numpy(grid.GetPoints().GetData()).astype(float)


def read_vtu(path):
    """(points (n x 3), {name: point field}) of every point of PATH."""
    grid = read_grid(path)
    return points_of(grid), point_fields(grid)


def read_contact_nodes(path):
    """(points (n x 3), {name: point field}) of the contact nodes of a
    contact-surface file (status >= 0), each once, in the order of their
    first appearance."""
    points, fields = read_vtu(path)
    if "status" not in fields:
        raise ValueError(f"{path}: no `status' field (not a contact surface)")
    keep = fields["status"] != NO_CONTACT_NODE
    points = points[keep]
    fields = {name: values[keep] for name, values in fields.items()}
    if len(points):
        _, first = numpy.unique(points, axis=0, return_index=True)
        order = numpy.sort(first)
        points = points[order]
        fields = {name: values[order] for name, values in fields.items()}
    return points, fields


def integrate(grid):
    """What ParaView's Integrate Variables gives (its filter,
    vtkIntegrateAttributes): {point field name: integral over the cells} and
    `Length' (2D lines) / `Area' (3D quadrilaterals).  A quadrilateral is
    integrated as the two triangles (0, 1, 2) and (0, 2, 3) with linear
    interpolation on each (lib/io/README.md)."""
    require_vtk()
    integrator = vtkIntegrateAttributes()
    integrator.SetInputData(grid)
    integrator.Update()
    out = integrator.GetOutput()
    values = {}
    for i in range(out.GetPointData().GetNumberOfArrays()):
        array = out.GetPointData().GetArray(i)
        values[array.GetName()] = (array.GetTuple(0) if
                                   array.GetNumberOfComponents() > 1
                                   else array.GetValue(0))
    for i in range(out.GetCellData().GetNumberOfArrays()):
        array = out.GetCellData().GetArray(i)
        values[array.GetName()] = array.GetValue(0)
    return values
