#!/usr/bin/python3
"""The standard picture of a dualcontact result, rendered with VTK to a PNG.

Usage (off-screen under a virtual X server; scripts/setup --render installs
xvfb):
  xvfb-run -a /usr/bin/python3 postprocess/render_vtu.py RESULT OUTPUT.png
      [--warp auto|S] [--view iso|+x|-x|+y|-y|+z|-z] [--title TEXT]
      [--size 1600 800]

RESULT: an output folder or its solution.pvd.  Two panels:
  left:  the bodies (solution.pvtu), displaced by S times displacement_m
         (auto: the largest displacement shown as 5 % of the scene's size;
         0: undeformed), coloured by von_mises_stress_Pa;
  right: the contact surfaces (contact_N.vtu / .pvtu of solution.pvd) alone,
         coloured by pressure_Pa, seen from the master side along their mean
         normal (3D) or from +z (2D), cell edges drawn.
A scene without contact pairs gets the left panel only.  --view: the left
panel's camera ("+z" looks down onto the x-y plane; iso from (1, -1.2, 0.8);
default iso in 3D, +z in 2D).

Reads through VTK's Python module (Debian's python3-vtk9, under
/usr/bin/python3; postprocess/contact_vtu.py), not ParaView: Debian 12's
python3-paraview conflicts with python3-vtk9 (README.md, *Postprocessing*).
postprocess/render_paraview.py is the ParaView counterpart with more options.
"""
import argparse
import os
import re
import sys
import xml.etree.ElementTree as ET

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import contact_vtu  # noqa: E402

contact_vtu.require_vtk()
import numpy  # noqa: E402
import vtkmodules.vtkInteractionStyle  # noqa: E402,F401
import vtkmodules.vtkRenderingFreeType  # noqa: E402,F401
import vtkmodules.vtkRenderingOpenGL2  # noqa: E402,F401
from vtkmodules.vtkFiltersGeneral import vtkWarpVector  # noqa: E402
from vtkmodules.vtkFiltersGeometry import vtkDataSetSurfaceFilter  # noqa: E402
from vtkmodules.vtkIOImage import vtkPNGWriter  # noqa: E402
from vtkmodules.vtkRenderingAnnotation import vtkScalarBarActor  # noqa: E402
from vtkmodules.vtkRenderingCore import (  # noqa: E402
    vtkActor, vtkColorTransferFunction, vtkDataSetMapper, vtkRenderer,
    vtkRenderWindow, vtkTextActor, vtkWindowToImageFilter)

# colour maps: (position in [0, 1], r, g, b)
TURBO = [(0.0, 0.19, 0.07, 0.23), (0.25, 0.16, 0.67, 0.93),
         (0.5, 0.45, 0.98, 0.37), (0.75, 0.98, 0.73, 0.22),
         (1.0, 0.48, 0.02, 0.01)]
INFERNO = [(0.0, 0.0, 0.0, 0.02), (0.25, 0.34, 0.06, 0.43),
           (0.5, 0.73, 0.21, 0.33), (0.75, 0.98, 0.55, 0.04),
           (1.0, 0.99, 1.0, 0.64)]


def parse():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("result")
    p.add_argument("output")
    p.add_argument("--warp", default="auto")
    p.add_argument("--view")
    p.add_argument("--title", default="")
    p.add_argument("--size", type=int, nargs=2, default=[1600, 800])
    return p.parse_args()


def record_files(result):
    """(folder, body files, contact files) listed by solution.pvd; for a
    folder without one (`Write VTU = false'), its contact_N.vtu / .pvtu."""
    pvd = result if result.endswith(".pvd") else os.path.join(result,
                                                              "solution.pvd")
    folder = os.path.dirname(pvd)
    if os.path.isfile(pvd):
        files = [d.get("file") for d in
                 ET.parse(pvd).getroot().findall("Collection/DataSet")]
    elif os.path.isdir(folder):
        files = sorted(f for f in os.listdir(folder)
                       if re.fullmatch(r"contact_\d+\.p?vtu", f))
    else:
        sys.exit(f"render_vtu: {result} is no dualcontact output folder")
    bodies = [f for f in files if not os.path.basename(f).startswith("contact_")]
    contacts = [f for f in files if os.path.basename(f).startswith("contact_")]
    if not bodies and not contacts:
        sys.exit(f"render_vtu: {result}: no body or contact file")
    return folder, bodies, contacts


def colour_map(points, value_range):
    function = vtkColorTransferFunction()
    low, high = value_range
    if high <= low:
        high = low + 1.0
    for t, r, g, b in points:
        function.AddRGBPoint(low + t * (high - low), r, g, b)
    return function


def coloured_actor(data, field, lut, value_range):
    mapper = vtkDataSetMapper()
    mapper.SetInputData(data)
    mapper.SetScalarModeToUsePointFieldData()
    mapper.SelectColorArray(field)
    mapper.SetLookupTable(lut)
    mapper.SetScalarRange(*value_range)
    mapper.ScalarVisibilityOn()
    actor = vtkActor()
    actor.SetMapper(mapper)
    return actor


def scalar_bar(lut, title, x):
    bar = vtkScalarBarActor()
    bar.SetLookupTable(lut)
    bar.SetTitle(title)
    bar.SetNumberOfLabels(3)
    bar.SetLabelFormat("%-#.3g")
    bar.SetOrientationToHorizontal()
    bar.SetPosition(x, 0.02)
    bar.SetWidth(0.36)
    bar.SetHeight(0.11)
    for prop in (bar.GetTitleTextProperty(), bar.GetLabelTextProperty()):
        prop.SetColor(0, 0, 0)
        prop.ShadowOff()
        prop.ItalicOff()
    return bar


def field_range(grid, field):
    array = grid.GetPointData().GetArray(field)
    if array is None:
        sys.exit(f"render_vtu: no point field `{field}'")
    return array.GetRange(-1 if array.GetNumberOfComponents() > 1 else 0)


def warped(grid, vectors, scale):
    if scale == 0:
        return grid
    grid.GetPointData().SetActiveVectors(vectors)
    warp = vtkWarpVector()
    warp.SetInputData(grid)
    warp.SetScaleFactor(scale)
    warp.Update()
    return warp.GetOutput()


def camera(renderer, direction, up, parallel):
    cam = renderer.GetActiveCamera()
    cam.SetFocalPoint(0, 0, 0)
    cam.SetPosition(*direction)
    cam.SetViewUp(*up)
    cam.SetParallelProjection(parallel)
    renderer.ResetCamera()
    cam.Zoom(0.9)


def text(renderer, words, x, y):
    actor = vtkTextActor()
    actor.SetInput(words)
    actor.GetTextProperty().SetColor(0, 0, 0)
    actor.GetTextProperty().SetFontSize(18)
    actor.SetPosition(x, y)
    renderer.AddActor2D(actor)


def bodies_panel(a, bodies, contacts, size):
    """The deformed bodies by von Mises stress: (renderer, displacement
    scale, dimension)."""
    bounds = numpy.array(bodies.GetBounds()).reshape(3, 2)
    dim = 2 if bounds[2, 1] - bounds[2, 0] == 0 else 3
    u_max = field_range(bodies, "displacement_m")[1]
    scale = (0.05 * size / u_max if u_max > 0 else 0.0) \
        if a.warp == "auto" else float(a.warp)
    surface = vtkDataSetSurfaceFilter()
    surface.SetInputData(warped(bodies, "displacement_m", scale))
    surface.Update()
    stress_range = field_range(bodies, "von_mises_stress_Pa")
    stress_lut = colour_map(TURBO, stress_range)
    left = vtkRenderer()
    left.SetBackground(1, 1, 1)
    left.AddActor(coloured_actor(surface.GetOutput(), "von_mises_stress_Pa",
                                 stress_lut, stress_range))
    left.AddActor2D(scalar_bar(stress_lut, "von_mises_stress_Pa", 0.07))
    views = {"+x": ((1, 0, 0), (0, 0, 1)), "-x": ((-1, 0, 0), (0, 0, 1)),
             "+y": ((0, 1, 0), (0, 0, 1)), "-y": ((0, -1, 0), (0, 0, 1)),
             "+z": ((0, 0, 1), (0, 1, 0)), "-z": ((0, 0, -1), (0, 1, 0)),
             "iso": ((1, -1.2, 0.8), (0, 0, 1))}
    view = a.view or ("iso" if dim == 3 else "+z")
    if view not in views:
        sys.exit("render_vtu: --view must be one of " + ", ".join(views))
    camera(left, *views[view], view != "iso")
    text(left, (a.title + "\n" if a.title else "")
         + "von Mises stress, displacements x %.3g" % scale,
         0.02 * a.size[0], 0.88 * a.size[1])
    return left, scale, dim


def pressure_colours(contacts):
    value_range = (0.0, max(field_range(c, "pressure_Pa")[1]
                            for c in contacts))
    return value_range, colour_map(INFERNO, value_range)


def contact_panel(a, contacts, dim, x0):
    """The contact surfaces by pressure, seen from the master side."""
    pressure_range, pressure_lut = pressure_colours(contacts)
    right = vtkRenderer()
    right.SetBackground(0.96, 0.96, 0.96)
    normal = numpy.zeros(3)
    for grid in contacts:
        fields = contact_vtu.point_fields(grid)
        normal += (fields["normal"] * fields["area_weight_m2"][:, None]
                   ).sum(axis=0)
        actor = coloured_actor(grid, "pressure_Pa", pressure_lut,
                               pressure_range)
        if dim == 3:
            actor.GetProperty().EdgeVisibilityOn()
            actor.GetProperty().SetEdgeColor(0.5, 0.5, 0.5)
        else:
            actor.GetProperty().SetLineWidth(8)
        right.AddActor(actor)
    right.AddActor2D(scalar_bar(pressure_lut, "pressure_Pa", x0 + 0.07))
    if dim == 3 and numpy.linalg.norm(normal) > 0:
        # from the master side, looking back at the slave surface
        n = normal / numpy.linalg.norm(normal)
        helper = numpy.array([0, 0, 1.0]) if abs(n[2]) < 0.9 \
            else numpy.array([0, 1.0, 0])
        camera(right, n, helper - (helper @ n) * n, 1)
    else:
        camera(right, (0, 0, 1), (0, 1, 0), 1)
    text(right, ("" if x0 > 0 or not a.title else a.title + "\n")
         + "contact surface%s by pressure, seen from the master side"
         % ("s" if len(contacts) > 1 else ""),
         (x0 + 0.02) * a.size[0], 0.88 * a.size[1])
    return right


def main():
    a = parse()
    folder, body_files, contact_files = record_files(a.result)
    contacts = [contact_vtu.read_grid(os.path.join(folder, f))
                for f in contact_files]
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(*a.size)
    scale, dim = 0.0, 3
    if body_files:
        bodies = contact_vtu.read_grid(os.path.join(folder, body_files[0]))
        bounds = numpy.array(bodies.GetBounds()).reshape(3, 2)
        size = numpy.linalg.norm(bounds[:, 1] - bounds[:, 0])
        left, scale, dim = bodies_panel(a, bodies, contacts, size)
        left.SetViewport(0, 0, 0.5 if contacts else 1, 1)
        window.AddRenderer(left)
    elif contacts and contacts[0].GetNumberOfCells() > 0:
        dim = 2 if contacts[0].GetCellType(0) == 3 else 3  # VTK_LINE
    if contacts:
        x0 = 0.5 if body_files else 0.0
        right = contact_panel(a, contacts, dim, x0)
        right.SetViewport(x0, 0, 1, 1)
        window.AddRenderer(right)

    window.Render()
    image = vtkWindowToImageFilter()
    image.SetInput(window)
    image.Update()
    writer = vtkPNGWriter()
    writer.SetFileName(a.output)
    writer.SetInputConnection(image.GetOutputPort())
    writer.Write()
    print(f"render_vtu: wrote {a.output}"
          + (f" (displacements x {scale:.3g})" if body_files else ""))


if __name__ == "__main__":
    main()
