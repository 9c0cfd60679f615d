#!/usr/bin/python3
"""The contact surfaces of a dualcontact run, read back with VTK.

Usage: check_contact_surface.py DUALCONTACT INPUT.prm WORKDIR [--cells N]
           [--exact REL] [--paraview REL] [--hanging] [--beyond]
           [--mpirun MPIRUN --ranks N]

Runs INPUT.prm in WORKDIR (under MPIRUN on N processes with --ranks) and
asserts, for every contact pair N, of contact_N.vtu (contact_N.pvtu and its
pieces under MPI), read with VTK's XML readers (postprocess/contact_vtu.py):
  - it is listed in solution.pvd; its data arrays are binary and
    zlib-compressed;
  - its cells are all lines (2D) or quadrilaterals (3D), pair 1 has
    --cells of them;
  - the point fields pressure_Pa, normal_force_N, area_weight_m2, gap_m,
    status (1 component), tangential_traction_Pa, slip_m, normal (3);
  - its contact nodes (status >= 0, each once) are pair_N.n_nodes of
    results.txt, normal_force_N = pressure_Pa * area_weight_m2 at each, and
    their sum is pair_N.normal_force to 1e-12;
  - the integral of the piecewise linear (2D) / bilinear (3D) interpolant of
    pressure_Pa over the cells (2-point Gauss per direction on each cell, the
    quadrature of the area weights) equals pair_N.normal_force to --exact
    (default 1e-10: exact for Q1, sum_i p_i int phi_i ds = sum_i lambda_N,i);
  - ParaView's Integrate Variables (vtkIntegrateAttributes) of pressure_Pa
    equals pair_N.normal_force to --paraview (default 1e-10; it integrates
    a quadrilateral as two linear triangles, lib/io/README.md);
  - --hanging: some points are hanging nodes (status -1 with a finite gap,
    interpolated from contact nodes); --beyond: some points lie beyond the
    search distance (status -1, pressure 0, gap NaN).
Prints the measured values.  2D: forces per metre of thickness.
"""
import argparse
import math
import os
import re
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "postprocess"))
import contact_vtu  # noqa: E402
import numpy  # noqa: E402

failures = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what)
    if not ok:
        failures.append(what)


def read_results(path):
    values = {}
    for line in open(path):
        if "=" in line and not line.startswith("#"):
            key, value = line.split("=", 1)
            try:
                values[key.strip()] = [float(v) for v in value.split(",")]
            except ValueError:
                pass
    return values


def gauss_integral(grid, name, dim):
    """(integral of the interpolant of point field NAME, measure) over the
    cells: lines exactly, quadrilaterals with the bilinear map and 2 x 2
    Gauss points."""
    points = contact_vtu.points_of(grid)
    values = contact_vtu.point_fields(grid)[name]
    g = 0.5 / math.sqrt(3.0)
    gauss = [0.5 - g, 0.5 + g]
    integral = measure = 0.0
    for c in range(grid.GetNumberOfCells()):
        ids = grid.GetCell(c).GetPointIds()
        v = [ids.GetId(k) for k in range(ids.GetNumberOfIds())]
        if dim == 2:
            length = numpy.linalg.norm(points[v[1]] - points[v[0]])
            integral += 0.5 * length * (values[v[0]] + values[v[1]])
            measure += length
            continue
        x = points[v]
        p = values[v]
        for s in gauss:
            for t in gauss:
                shape = numpy.array([(1 - s) * (1 - t), s * (1 - t), s * t,
                                     (1 - s) * t])
                d_s = numpy.array([-(1 - t), 1 - t, t, -t]) @ x
                d_t = numpy.array([-(1 - s), -s, s, 1 - s]) @ x
                jxw = 0.25 * numpy.linalg.norm(numpy.cross(d_s, d_t))
                integral += jxw * (shape @ p)
                measure += jxw
    return integral, measure


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("app")
    parser.add_argument("prm")
    parser.add_argument("workdir")
    parser.add_argument("--cells", type=int)
    parser.add_argument("--exact", type=float, default=1e-10)
    parser.add_argument("--paraview", type=float, default=1e-10)
    parser.add_argument("--hanging", action="store_true")
    parser.add_argument("--beyond", action="store_true")
    parser.add_argument("--mpirun")
    parser.add_argument("--ranks", type=int, default=1)
    a = parser.parse_args()
    contact_vtu.require_vtk()

    shutil.rmtree(a.workdir, ignore_errors=True)
    os.makedirs(a.workdir)
    command = [a.app, os.path.abspath(a.prm)]
    env = dict(os.environ)
    if a.ranks > 1:
        command = [a.mpirun, "--allow-run-as-root", "--oversubscribe", "-np",
                   str(a.ranks)] + command
        env.update({"OMPI_ALLOW_RUN_AS_ROOT": "1",
                    "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
                    "OMP_NUM_THREADS": "1"})
    run = subprocess.run(command, cwd=a.workdir, capture_output=True,
                         text=True, env=env)
    print(run.stdout[-2000:])
    if run.returncode != 0:
        print(run.stderr[-3000:])
        sys.exit(f"dualcontact failed with exit code {run.returncode}")
    folder = os.path.join(a.workdir, "output")
    results = read_results(os.path.join(folder, "results.txt"))
    dim = int(results["dimension"][0])
    unit = "N/m (per metre of thickness)" if dim == 2 else "N"
    with open(os.path.join(folder, "solution.pvd")) as f:
        pvd = f.read()

    pair = 1
    while f"pair_{pair}.n_nodes" in results:
        name = f"contact_{pair}." + ("pvtu" if a.ranks > 1 else "vtu")
        path = os.path.join(folder, name)
        check(os.path.isfile(path) and f'file="{name}"' in pvd,
              f"{name} written and listed in solution.pvd")
        files = [path]
        if a.ranks > 1:
            files = [os.path.join(folder, piece) for piece in
                     re.findall(r'Source="([^"]+)"', open(path).read())]
            check(len(files) == a.ranks, f"{len(files)} pieces in {name}")
        compressed = all(
            'format="binary"' in text and "vtkZLibDataCompressor" in text
            and 'format="ascii"' not in text
            for text in (open(f, errors="replace").read() for f in files))
        check(compressed, f"{name}: binary, zlib-compressed data arrays")

        grid = contact_vtu.read_grid(path)
        n_cells = grid.GetNumberOfCells()
        cell_type = 3 if dim == 2 else 9  # VTK_LINE, VTK_QUAD
        types = {grid.GetCellType(c) for c in range(n_cells)}
        check(n_cells > 0 and types == {cell_type},
              f"{name}: {n_cells} cells, all "
              + ("lines" if dim == 2 else "quadrilaterals"))
        if pair == 1 and a.cells is not None:
            check(n_cells == a.cells, f"{name}: {n_cells} cells, expected "
                  f"{a.cells}")
        fields = contact_vtu.point_fields(grid)
        expected = {"pressure_Pa": 1, "normal_force_N": 1,
                    "area_weight_m2": 1, "gap_m": 1, "status": 1,
                    "tangential_traction_Pa": 3, "slip_m": 3, "normal": 3}
        shapes = {k: (1 if v.ndim == 1 else v.shape[1])
                  for k, v in fields.items()}
        check(all(shapes.get(k) == n for k, n in expected.items()),
              f"{name}: fields {shapes}")

        _, nodes = contact_vtu.read_contact_nodes(path)
        n_nodes = len(nodes["pressure_Pa"])
        check(n_nodes == results[f"pair_{pair}.n_nodes"][0],
              f"{name}: {n_nodes} contact nodes, n_nodes = "
              f"{results[f'pair_{pair}.n_nodes'][0]:g}")
        force = results[f"pair_{pair}.normal_force"][0]
        product = numpy.abs(nodes["normal_force_N"] - nodes["pressure_Pa"]
                            * nodes["area_weight_m2"]).max()
        check(product <= 1e-12 * max(force, 1e-300),
              f"normal_force_N = pressure_Pa * area_weight_m2 (largest "
              f"difference {product:.2e} {unit})")
        total = float(nodes["normal_force_N"].sum())
        check(abs(total - force) <= 1e-12 * abs(force),
              f"sum of normal_force_N {total:.12e} {unit}, results.txt "
              f"{force:.12e}")

        exact, measure = gauss_integral(grid, "pressure_Pa", dim)
        error = abs(exact - force) / abs(force)
        check(error <= a.exact,
              f"integral of the interpolated pressure {exact:.12e} {unit}: "
              f"relative difference {error:.2e} (limit {a.exact:.0e})")
        paraview = contact_vtu.integrate(grid)
        integral = paraview["pressure_Pa"]
        error = abs(integral - force) / abs(force)
        check(error <= a.paraview,
              f"Integrate Variables of pressure_Pa {integral:.12e} {unit}: "
              f"relative difference {error:.2e} (limit {a.paraview:.0e}); "
              f"{'Length' if dim == 2 else 'Area'} "
              f"{paraview.get('Length' if dim == 2 else 'Area', 0):.6g}, "
              f"Gauss {measure:.6g}")

        status = fields["status"]
        other = status == contact_vtu.NO_CONTACT_NODE
        hanging = int((other & numpy.isfinite(fields["gap_m"])).sum())
        beyond = int((other & numpy.isnan(fields["gap_m"])).sum())
        print(f"      {name}: {hanging} hanging points, {beyond} beyond the "
              "search distance")
        if a.hanging and pair == 1:
            check(hanging > 0, f"{name}: hanging nodes among the points")
        if a.beyond and pair == 1:
            check(beyond > 0 and numpy.all(fields["pressure_Pa"][
                other & numpy.isnan(fields["gap_m"])] == 0),
                f"{name}: points beyond the search distance, pressure 0")
        pair += 1
    check(pair > 1, "the scene has contact pairs")
    if failures:
        sys.exit(f"{len(failures)} check(s) failed")
    print("all checks passed")


if __name__ == "__main__":
    main()
