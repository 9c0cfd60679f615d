#!/usr/bin/python3
"""The standard picture of a dualcontact result, rendered with VTK to a PNG.

Usage (off-screen under a virtual X server; scripts/setup --render installs
xvfb):
  xvfb-run -a /usr/bin/python3 postprocess/render_vtu.py RESULT OUTPUT.png
      [--warp auto|S] [--view iso|+x|-x|+y|-y|+z|-z] [--title TEXT]
      [--size 1600 800] [--field NAME] [--contact-field NAME]
      [--panels both|bodies|contact] [--status] [--contact-view VIEW]
      [--time T]

RESULT: an output folder or its solution.pvd.  Two panels:
  left:  the bodies (solution.pvtu), displaced by S times displacement_m
         (auto: the largest displacement shown as 5 % of the scene's size;
         0: undeformed), coloured by von_mises_stress_Pa;
  right: the contact surfaces (contact_N.vtu / .pvtu of solution.pvd) alone,
         coloured by pressure_Pa, seen from the master side along their mean
         normal (3D) or from +z (2D), cell edges drawn.
A scene without contact pairs gets the left panel only.  --view: the left
panel's camera ("+z" looks down onto the x-y plane; iso from (1, -1.2, 0.8);
default iso in 3D, +z in 2D).  --field / --contact-field: the point field
of the left / right panel (vectors by their magnitude; defaults
von_mises_stress_Pa / pressure_Pa).  --panels: both (default), or one of
them alone (the whole picture).  --contact-view: the right panel's camera
(the views of --view; default: from the master side).  --status: the
contact nodes as dots in discrete colours by their `status' (0
separated, 1 stick, 2 slip, 3 in contact without friction; -1 no contact
node), with a legend and the number of nodes in each state: on the
deformed bodies (each dot moved with the bodies' displacement at its
place) and on the contact surfaces.  --time: the record of a load
history's solution.pvd to draw, the one whose time is nearest T (default:
the last step; one record per step, drawing all of them would overlay the
steps).

Reads through VTK's Python module (Debian's python3-vtk9, under
/usr/bin/python3; postprocess/contact_vtu.py), not ParaView: Debian 12's
python3-paraview conflicts with python3-vtk9 (doc/manual/output.md, "Postprocessing").
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
    vtkActor, vtkColorTransferFunction, vtkDataSetMapper, vtkPolyDataMapper,
    vtkRenderer, vtkRenderWindow, vtkTextActor, vtkWindowToImageFilter)
from vtkmodules.vtkCommonCore import (  # noqa: E402
    vtkIdList, vtkLookupTable, vtkPoints, vtkVariant)
from vtkmodules.vtkCommonDataModel import (  # noqa: E402
    vtkImageData, vtkPolyData, vtkStaticPointLocator)
from vtkmodules.vtkFiltersGeneral import vtkVertexGlyphFilter  # noqa: E402
from vtkmodules.vtkRenderingAnnotation import vtkLegendBoxActor  # noqa: E402
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy  # noqa: E402

# colour maps: (position in [0, 1], r, g, b)
TURBO = [(0.0, 0.19, 0.07, 0.23), (0.25, 0.16, 0.67, 0.93),
         (0.5, 0.45, 0.98, 0.37), (0.75, 0.98, 0.73, 0.22),
         (1.0, 0.48, 0.02, 0.01)]
INFERNO = [(0.0, 0.0, 0.0, 0.02), (0.25, 0.34, 0.06, 0.43),
           (0.5, 0.73, 0.21, 0.33), (0.75, 0.98, 0.55, 0.04),
           (1.0, 0.99, 1.0, 0.64)]


# the contact states of contact_N.vtu's `status' (lib/io/contact_surface_writer.h)
STATUS = [(-1, "no contact node", (0.75, 0.75, 0.75)),
          (0, "separated", (1.0, 1.0, 1.0)),
          (1, "stick", (0.0, 0.0, 0.0)),
          (2, "slip", (0.9, 0.0, 0.9)),
          (3, "in contact (frictionless)", (0.0, 0.0, 0.0))]

VIEWS = {"+x": ((1, 0, 0), (0, 0, 1)), "-x": ((-1, 0, 0), (0, 0, 1)),
         "+y": ((0, 1, 0), (0, 0, 1)), "-y": ((0, -1, 0), (0, 0, 1)),
         "+z": ((0, 0, 1), (0, 1, 0)), "-z": ((0, 0, -1), (0, 1, 0)),
         "iso": ((1, -1.2, 0.8), (0, 0, 1))}


def parse():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("result")
    p.add_argument("output")
    p.add_argument("--warp", default="auto")
    p.add_argument("--view")
    p.add_argument("--title", default="")
    p.add_argument("--size", type=int, nargs=2, default=[1600, 800])
    p.add_argument("--field", default="von_mises_stress_Pa")
    p.add_argument("--contact-field", default="pressure_Pa")
    p.add_argument("--panels", choices=["both", "bodies", "contact"],
                   default="both")
    p.add_argument("--contact-view")
    p.add_argument("--status", action="store_true")
    p.add_argument("--time", type=float)
    return p.parse_args()


def record_files(result, time=None):
    """(folder, body files, contact files) listed by solution.pvd at the
    record nearest @p time (None: the last one; a load history writes one
    record per step); for a folder without one (`Write VTU = false'), its
    contact_N.vtu / .pvtu."""
    pvd = result if result.endswith(".pvd") else os.path.join(result,
                                                              "solution.pvd")
    folder = os.path.dirname(pvd)
    if os.path.isfile(pvd):
        records = ET.parse(pvd).getroot().findall("Collection/DataSet")
        times = sorted({float(d.get("timestep", "0")) for d in records})
        if not times:
            sys.exit(f"render_vtu: {pvd}: no record")
        chosen = (times[-1] if time is None
                  else min(times, key=lambda t: abs(t - time)))
        files = [d.get("file") for d in records
                 if float(d.get("timestep", "0")) == chosen]
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


def status_lookup(present):
    """A categorical lookup table of the states in PRESENT: one colour and
    one legend entry each."""
    lut = vtkLookupTable()
    states = [t for t in STATUS if t[0] in present]
    lut.SetNumberOfTableValues(len(states))
    lut.IndexedLookupOn()
    for i, (value, label, rgb) in enumerate(states):
        lut.SetTableValue(i, *rgb, 1.0)
        lut.SetAnnotation(vtkVariant(value), label)
    lut.Build()
    return lut


def status_dots(points, status, lut, size):
    """The contact nodes as dots coloured by their status."""
    cloud = vtkPolyData()
    vtk_points = vtkPoints()
    for p in points:
        vtk_points.InsertNextPoint(*p)
    cloud.SetPoints(vtk_points)
    array = numpy_to_vtk(numpy.asarray(status, dtype=numpy.int32), deep=1)
    array.SetName("status")
    cloud.GetPointData().AddArray(array)
    vertices = vtkVertexGlyphFilter()
    vertices.SetInputData(cloud)
    vertices.Update()
    mapper = vtkPolyDataMapper()
    mapper.SetInputData(vertices.GetOutput())
    mapper.SetScalarModeToUsePointFieldData()
    mapper.SelectColorArray("status")
    mapper.SetLookupTable(lut)
    mapper.UseLookupTableScalarRangeOn()
    mapper.ScalarVisibilityOn()
    actor = vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().SetPointSize(size)
    actor.GetProperty().RenderPointsAsSpheresOn()
    return actor


def dot_icon(rgb, size=32):
    """A round dot of colour RGB with a dark rim on a transparent square."""
    y, x = numpy.mgrid[0:size, 0:size] + 0.5 - size / 2
    r = numpy.hypot(x, y) / (size / 2)
    pixels = numpy.zeros((size, size, 4), dtype=numpy.uint8)
    pixels[r <= 0.8, :3] = numpy.array(rgb) * 255
    pixels[(r > 0.8) & (r <= 0.95), :3] = 60
    pixels[r <= 0.95, 3] = 255
    icon = vtkImageData()
    icon.SetDimensions(size, size, 1)
    array = numpy_to_vtk(pixels.reshape(-1, 4), deep=1)
    array.SetName("rgba")
    icon.GetPointData().SetScalars(array)
    return icon


def status_legend(lut, x, counts):
    """The legend of the contact states: a dot in each state's discrete
    colour, its name and (COUNTS) its number of nodes."""
    legend = vtkLegendBoxActor()
    states = [t for t in STATUS
              if lut.GetAnnotatedValueIndex(vtkVariant(t[0])) >= 0]
    legend.SetNumberOfEntries(len(states))
    # the dot is the icon; the symbol (drawn in the text colour) is a
    # single point without cells, i.e. nothing
    no_symbol = vtkPolyData()
    no_symbol.SetPoints(vtkPoints())
    no_symbol.GetPoints().InsertNextPoint(0, 0, 0)
    for i, (value, label, rgb) in enumerate(states):
        legend.SetEntry(i, no_symbol, dot_icon(rgb),
                        "%s (%d)" % (label, counts.get(value, 0)),
                        (0.0, 0.0, 0.0))
    legend.UseBackgroundOn()
    legend.SetBackgroundColor(0.88, 0.88, 0.88)
    legend.BorderOn()
    legend.GetEntryTextProperty().SetColor(0, 0, 0)
    legend.GetEntryTextProperty().ShadowOff()
    legend.GetPositionCoordinate().SetCoordinateSystemToNormalizedViewport()
    legend.GetPositionCoordinate().SetValue(x, 0.03)
    legend.GetPosition2Coordinate().SetCoordinateSystemToNormalizedViewport()
    legend.GetPosition2Coordinate().SetValue(0.25, 0.05 * len(states) + 0.02)
    return legend


def counts_of(status):
    values, counts = numpy.unique(status, return_counts=True)
    return dict(zip(values.tolist(), counts.tolist()))


def contact_states(contacts):
    """(points, status) of the contact surfaces' points, each place once:
    where several pairs share a slave surface (a node against two walls),
    the state of the pair it is most engaged with (the largest status:
    slip / contact over stick over separated over no contact node)."""
    merged = {}
    for c in contacts:
        if c.GetNumberOfPoints() == 0:
            continue
        for p, state in zip(contact_vtu.points_of(c),
                            contact_vtu.point_fields(c)["status"]):
            key = tuple(numpy.round(p, 12))
            merged[key] = max(merged.get(key, -2), int(state))
    points = numpy.array(list(merged.keys()), dtype=float).reshape(-1, 3)
    return points, numpy.array(list(merged.values()), dtype=int)


def displaced(points, bodies, scale):
    """POINTS moved by SCALE times the bodies' displacement there: the mean
    over the bodies' points at the same place (both sides of a matching
    interface)."""
    if scale == 0 or len(points) == 0:
        return points
    locator = vtkStaticPointLocator()
    locator.SetDataSet(bodies)
    locator.BuildLocator()
    u = contact_vtu.point_fields(bodies)["displacement_m"]
    bounds = numpy.array(bodies.GetBounds()).reshape(3, 2)
    radius = 1e-8 * numpy.linalg.norm(bounds[:, 1] - bounds[:, 0])
    moved = numpy.array(points, dtype=float)
    found = vtkIdList()
    for i, p in enumerate(points):
        locator.FindPointsWithinRadius(radius, p, found)
        ids = [found.GetId(k) for k in range(found.GetNumberOfIds())]
        if not ids:
            ids = [locator.FindClosestPoint(p)]
        moved[i] += scale * u[ids].mean(axis=0)
    return moved


def scalar_bar(lut, title, x):
    bar = vtkScalarBarActor()
    bar.SetLookupTable(lut)
    bar.SetTitle(title)
    bar.SetNumberOfLabels(3)
    bar.SetLabelFormat("%-#.3g")
    bar.SetOrientationToHorizontal()
    bar.SetPosition(x, 0.02)
    bar.SetWidth(0.42)
    bar.SetHeight(0.1)
    bar.UnconstrainedFontSizeOn()
    bar.GetTitleTextProperty().SetFontSize(18)
    bar.GetLabelTextProperty().SetFontSize(15)
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


def camera(renderer, direction, up, parallel, zoom=0.9):
    cam = renderer.GetActiveCamera()
    cam.SetFocalPoint(0, 0, 0)
    cam.SetPosition(*direction)
    cam.SetViewUp(*up)
    cam.SetParallelProjection(parallel)
    renderer.ResetCamera()
    cam.Zoom(zoom)


def text(renderer, words, x, y):
    actor = vtkTextActor()
    actor.SetInput(words)
    actor.GetTextProperty().SetColor(0, 0, 0)
    actor.GetTextProperty().SetFontSize(18)
    actor.SetPosition(x, y)
    renderer.AddActor2D(actor)


def bodies_panel(a, bodies, contacts, size):
    """The deformed bodies by --field (von Mises stress): (renderer,
    displacement scale, dimension)."""
    bounds = numpy.array(bodies.GetBounds()).reshape(3, 2)
    dim = 2 if bounds[2, 1] - bounds[2, 0] == 0 else 3
    u_max = field_range(bodies, "displacement_m")[1]
    scale = (0.05 * size / u_max if u_max > 0 else 0.0) \
        if a.warp == "auto" else float(a.warp)
    surface = vtkDataSetSurfaceFilter()
    surface.SetInputData(warped(bodies, "displacement_m", scale))
    surface.Update()
    body_range = field_range(bodies, a.field)
    body_lut = colour_map(TURBO, body_range)
    body_lut.SetVectorModeToMagnitude()
    left = vtkRenderer()
    left.SetBackground(1, 1, 1)
    left.AddActor(coloured_actor(surface.GetOutput(), a.field,
                                 body_lut, body_range))
    with_legend = a.status and contacts
    left.AddActor2D(scalar_bar(body_lut, a.field,
                               0.07))
    if a.status and contacts:
        points, status = contact_states(contacts)
        lut = status_lookup(set(status.tolist()))
        left.AddActor(status_dots(displaced(points, bodies, scale), status,
                                  lut, 14))
        left.AddActor2D(status_legend(lut, 0.62, counts_of(status)))
    view = a.view or ("iso" if dim == 3 else "+z")
    if view not in VIEWS:
        sys.exit("render_vtu: --view must be one of " + ", ".join(VIEWS))
    camera(left, *VIEWS[view], view != "iso")
    name = "von Mises stress" if a.field == "von_mises_stress_Pa" else a.field
    text(left, (a.title + "\n" if a.title else "")
         + "%s, displacements x %.3g" % (name, scale)
         + ("; contact nodes by status" if a.status and contacts else ""),
         0.02 * a.size[0], 0.88 * a.size[1])
    return left, scale, dim


def merged_surfaces(contacts, field):
    """Pairs that share one slave surface (the same points: a disc against
    two walls) drawn once, with FIELD at each point taken from the pair
    where it is largest in magnitude (e.g. the pressure of the wall the
    node presses on); otherwise the later pair would hide the earlier."""
    kept = []
    for grid in contacts:
        twin = None
        for k, other in enumerate(kept):
            if (other.GetNumberOfPoints() == grid.GetNumberOfPoints() > 0
                    and numpy.allclose(contact_vtu.points_of(other),
                                       contact_vtu.points_of(grid))):
                twin = k
        if twin is None:
            kept.append(grid)
            continue
        merged = kept[twin].NewInstance()
        merged.DeepCopy(kept[twin])
        mine = merged.GetPointData().GetArray(field)
        theirs = grid.GetPointData().GetArray(field)
        a, b = vtk_to_numpy(mine), vtk_to_numpy(theirs)
        size = (lambda v: numpy.abs(v) if v.ndim == 1
                else numpy.linalg.norm(v, axis=1))
        pick = size(b) > size(a)
        a[pick] = b[pick]
        mine.Modified()
        kept[twin] = merged
    return kept


def contact_colours(contacts, field):
    ranges = [field_range(c, field) for c in contacts]
    value_range = (min(0.0, min(r[0] for r in ranges)),
                   max(r[1] for r in ranges))
    lut = colour_map(INFERNO, value_range)
    lut.SetVectorModeToMagnitude()
    return value_range, lut


def contact_panel(a, contacts, dim, x0):
    """The contact surfaces by --contact-field (pressure), seen from the
    master side (or --contact-view)."""
    field = a.contact_field
    points, status = contact_states(contacts)   # every pair's states
    contacts = merged_surfaces(contacts, field)
    field_range_, field_lut = contact_colours(contacts, field)
    right = vtkRenderer()
    right.SetBackground(0.96, 0.96, 0.96)
    normal = numpy.zeros(3)
    for grid in contacts:
        fields = contact_vtu.point_fields(grid)
        normal += (fields["normal"] * fields["area_weight_m2"][:, None]
                   ).sum(axis=0)
        actor = coloured_actor(grid, field, field_lut, field_range_)
        if dim == 3:
            actor.GetProperty().EdgeVisibilityOn()
            actor.GetProperty().SetEdgeColor(0.5, 0.5, 0.5)
        else:
            actor.GetProperty().SetLineWidth(8)
        right.AddActor(actor)
    legend_here = a.status and a.panels == "contact"
    right.AddActor2D(scalar_bar(field_lut, field,
                                0.07 if legend_here else 0.5))
    if a.status:
        lut = status_lookup(set(status.tolist()))
        right.AddActor(status_dots(points, status, lut, 14))
        if legend_here:
            right.AddActor2D(status_legend(lut, 0.62, counts_of(status)))
    if a.contact_view:
        if a.contact_view not in VIEWS:
            sys.exit("render_vtu: --contact-view must be one of "
                     + ", ".join(VIEWS))
        camera(right, *VIEWS[a.contact_view], a.contact_view != "iso",
               0.9 if x0 > 0 else 0.72)
    elif dim == 3 and numpy.linalg.norm(normal) > 0:
        # from the master side, looking back at the slave surface
        n = normal / numpy.linalg.norm(normal)
        helper = numpy.array([0, 0, 1.0]) if abs(n[2]) < 0.9 \
            else numpy.array([0, 1.0, 0])
        camera(right, n, helper - (helper @ n) * n, 1, 0.9 if x0 > 0 else 0.72)
    else:
        camera(right, (0, 0, 1), (0, 1, 0), 1)
    name = "pressure" if field == "pressure_Pa" else field
    text(right, ("" if x0 > 0 or not a.title else a.title + "\n")
         + "contact surface%s by %s, seen from %s"
         % ("s" if len(contacts) > 1 else "", name,
            "the master side" if not a.contact_view
            else "direction " + a.contact_view),
         (x0 + 0.02) * a.size[0], 0.88 * a.size[1])
    return right


def main():
    a = parse()
    folder, body_files, contact_files = record_files(a.result, a.time)
    contacts = [contact_vtu.read_grid(os.path.join(folder, f))
                for f in contact_files]
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(*a.size)
    scale, dim = 0.0, 3
    show_bodies = bool(body_files) and a.panels != "contact"
    show_contacts = bool(contacts) and a.panels != "bodies"
    if body_files:
        bodies = contact_vtu.read_grid(os.path.join(folder, body_files[0]))
        bounds = numpy.array(bodies.GetBounds()).reshape(3, 2)
        dim = 2 if bounds[2, 1] - bounds[2, 0] == 0 else 3
    elif contacts and contacts[0].GetNumberOfCells() > 0:
        dim = 2 if contacts[0].GetCellType(0) == 3 else 3  # VTK_LINE
    if show_bodies:
        size = numpy.linalg.norm(bounds[:, 1] - bounds[:, 0])
        left, scale, dim = bodies_panel(a, bodies, contacts, size)
        left.SetViewport(0, 0, 0.5 if show_contacts else 1, 1)
        window.AddRenderer(left)
    if show_contacts:
        x0 = 0.5 if show_bodies else 0.0
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
          + (f" (displacements x {scale:.3g})" if show_bodies else ""))


if __name__ == "__main__":
    main()
