#!/usr/bin/env python3
"""Renders a dualcontact output file (VTU, PVTU or PVD) to a PNG with ParaView.

Usage (ParaView's Python; off-screen under a virtual X server):
  xvfb-run -a /usr/bin/pvpython postprocess/render_paraview.py INPUT OUTPUT.png
      [--field von_mises_stress_Pa] [--component -1] [--view iso]
      [--warp 0] [--overlay FILE[:FIELD]] ... [--edges] [--title TEXT]
      [--size 1200 800] [--range MIN MAX] [--log]

INPUT: a .vtu / .pvtu (a body, all bodies, a contact surface) or a .pvd
(its last time step).  FIELD: a point array, coloured by its magnitude
(--component -1, default) or one component (0, 1, 2).  VIEW (write
--view=-z for a leading minus): +x, -x, +y, -y,
+z, -z (looking along minus that axis, i.e. from the + side: "+z" looks down
onto the x-y plane) or iso (from (1, -1.2, 0.8)).  --warp S: displace the
points by S times displacement_m (Warp By Vector) to show the deformation.
--overlay FILE[:FIELD]: draw another file in the same view (e.g. the contact
surface, as points coloured by FIELD, or plain grey without a field).
--edges: show the cell edges.  --points S: draw INPUT as points of S pixels.  The colour bar is titled by the field.
The ParaView counterpart of postprocess/render_vtu.py (which renders the
standard picture of a result with VTK alone, python3-vtk9).

Packages: Debian's paraview, python3-paraview, xvfb.  In Debian 12
python3-paraview conflicts with python3-vtk9, which libvtk9-dev (a build
dependency of dualcontact, scripts/setup) needs: installing one removes the
other.  Render on a machine (or container) without libvtk9-dev, or swap the
packages for the rendering and run scripts/setup afterwards (it puts
libvtk9-dev back, and the VTK read-back test io/vtu_output needs it).
"""
import argparse
import os
import sys

from paraview.simple import (ColorBy, CreateView, GetColorTransferFunction,
                             GetScalarBar, OpenDataFile, Render, SaveScreenshot, Show,
                             Text, UpdatePipeline, WarpByVector)


def parse():
    p = argparse.ArgumentParser()
    p.add_argument("input")
    p.add_argument("output")
    p.add_argument("--field", default="von_mises_stress_Pa")
    p.add_argument("--component", type=int, default=-1)
    p.add_argument("--view", default="iso")
    p.add_argument("--warp", type=float, default=0.0)
    p.add_argument("--overlay", action="append", default=[])
    p.add_argument("--edges", action="store_true")
    p.add_argument("--points", type=float, default=0.0)
    p.add_argument("--title", default="")
    p.add_argument("--size", type=int, nargs=2, default=[1200, 800])
    p.add_argument("--range", type=float, nargs=2)
    p.add_argument("--log", action="store_true")
    return p.parse_args()


def open_last_step(path):
    source = OpenDataFile(os.path.abspath(path))
    if source is None:
        sys.exit("render_vtu: cannot open " + path)
    times = list(getattr(source, "TimestepValues", None) or [])
    if times:
        source.UpdatePipeline(float(times[-1]))
    else:
        UpdatePipeline(proxy=source)
    return source


def colour(display, view, source, field, component, value_range, log):
    arrays = source.PointData.keys()
    if field not in arrays:
        sys.exit("render_vtu: no point field `%s' in %s (fields: %s)"
                 % (field, source.GetXMLName(), ", ".join(arrays)))
    n_components = source.PointData[field].GetNumberOfComponents()
    if n_components > 1 and component >= 0:
        ColorBy(display, ("POINTS", field, "%d" % component))
    elif n_components > 1:
        ColorBy(display, ("POINTS", field, "Magnitude"))
    else:
        ColorBy(display, ("POINTS", field))
    lut = GetColorTransferFunction(field)
    lut.ApplyPreset("Turbo" if "status" not in field else "Rainbow Uniform", True)
    if value_range:
        lut.RescaleTransferFunction(value_range[0], value_range[1])
    else:
        display.RescaleTransferFunctionToDataRange(False, True)
    if log:
        lut.UseLogScale = 1
    display.SetScalarBarVisibility(view, True)
    bar = GetScalarBar(lut, view)
    bar.Title = field + ("" if n_components == 1 else
                         (" [%d]" % component if component >= 0 else " (magnitude)"))
    bar.ComponentTitle = ""
    bar.TitleFontSize = 16
    bar.LabelFontSize = 14
    bar.TitleColor = [0, 0, 0]
    bar.LabelColor = [0, 0, 0]
    bar.ScalarBarLength = 0.5
    bar.RangeLabelFormat = "%-#.3g"
    bar.AddRangeLabels = 1


def main():
    a = parse()
    view = CreateView("RenderView")
    view.ViewSize = a.size
    view.Background = [1, 1, 1]
    try:
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    view.OrientationAxesVisibility = 1

    source = open_last_step(a.input)
    shown = source
    if a.warp != 0.0:
        shown = WarpByVector(Input=source)
        shown.Vectors = ["POINTS", "displacement_m"]
        shown.ScaleFactor = a.warp
    display = Show(shown, view)
    display.Representation = "Surface With Edges" if a.edges else "Surface"
    if a.points > 0:
        display.Representation = "Points"
        display.PointSize = a.points
        display.RenderPointsAsSpheres = 1
    if a.edges:
        display.EdgeColor = [0.3, 0.3, 0.3]
    colour(display, view, source, a.field, a.component, a.range, a.log)

    for overlay in a.overlay:
        path, _, field = overlay.partition(":")
        other = open_last_step(path)
        shown_other = other
        if a.warp != 0.0 and "displacement_m" in other.PointData.keys():
            shown_other = WarpByVector(Input=other)
            shown_other.Vectors = ["POINTS", "displacement_m"]
            shown_other.ScaleFactor = a.warp
        d = Show(shown_other, view)
        d.Representation = "Points"
        d.PointSize = 6
        d.RenderPointsAsSpheres = 1
        if field:
            colour(d, view, other, field, -1, None, False)
        else:
            ColorBy(d, None)
            d.AmbientColor = d.DiffuseColor = [0.2, 0.2, 0.2]

    if a.title:
        text = Text(Text=a.title)
        td = Show(text, view)
        td.FontSize = 14
        td.Color = [0, 0, 0]
        td.WindowLocation = "Upper Center"

    directions = {"+x": ([1, 0, 0], [0, 0, 1]), "-x": ([-1, 0, 0], [0, 0, 1]),
                  "+y": ([0, 1, 0], [0, 0, 1]), "-y": ([0, -1, 0], [0, 0, 1]),
                  "+z": ([0, 0, 1], [0, 1, 0]), "-z": ([0, 0, -1], [0, 1, 0]),
                  "iso": ([1, -1.2, 0.8], [0, 0, 1])}
    if a.view not in directions:
        sys.exit("render_vtu: --view must be one of " + ", ".join(directions))
    position, up = directions[a.view]
    view.CameraPosition = position
    view.CameraFocalPoint = [0, 0, 0]
    view.CameraViewUp = up
    view.ResetCamera()
    view.CameraParallelProjection = 1 if a.view != "iso" else 0
    view.ResetCamera()
    Render(view)
    SaveScreenshot(os.path.abspath(a.output), view, ImageResolution=a.size,
                   TransparentBackground=0)
    print("render_vtu: wrote " + a.output)


if __name__ == "__main__":
    main()
