#!/usr/bin/env python3
"""Runs a Hertz input of dualcontact and compares it with the closed form.

Usage: check_hertz.py DUALCONTACT INPUT.prm WORKDIR

INPUT.prm starts with `# Hertz: dim = D, R = .., P = .., E = .., nu = ..`: a
body of radius R (cylinder in 2D, per unit thickness; sphere in 3D) of
Young's modulus E and Poisson's ratio nu pressed onto a rigid plane by the
total force P on the full body.  The closed form is evaluated for the load
the discretized model carries (results.txt, body_1.applied_force, divided
by the model's fraction of the body), which differs from P by the error of
the polygonal loaded surface (3D).  The inputs model a half (2D: one symmetry
plane, the model carries P/2) or a quarter (3D: two symmetry planes, P/4).
With E* = E / (1 - nu^2):
  2D: a = sqrt(4 P R / (pi E*)),     p0 = 2 P / (pi a)
  3D: a = (3 P R / (4 E*))^(1/3),    p0 = 3 P / (2 pi a^2)
Asserted: total normal contact force (results.txt, pair_1.normal_force) =
the applied load (body_1.applied_force: the model's share of P on the
discretized loaded surface) to 1e-8 relative; contact radius / half-width
within 5 % of a (estimated as the midpoint between the outermost node in
contact and the innermost separated node beyond it, from contact_1.vtu);
peak nodal pressure within 10 % of p0.  Prints the measured errors.
"""
import glob
import math
import os
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET


def read_hertz_line(path):
    with open(path) as f:
        first = f.readline()
    m = re.match(r"#\s*Hertz:\s*(.*)", first)
    if not m:
        sys.exit(f"{path}: the first line is not a `# Hertz:' line")
    values = {}
    for item in m.group(1).split(","):
        key, value = item.split("=")
        values[key.strip()] = float(value)
    return values


def read_vtu(path):
    root = ET.parse(path).getroot()
    piece = root.find("UnstructuredGrid/Piece")
    points = [float(v) for v in piece.find("Points/DataArray").text.split()]
    points = [points[i:i + 3] for i in range(0, len(points), 3)]
    fields = {}
    for array in piece.find("PointData"):
        fields[array.get("Name")] = [float(v) for v in array.text.split()]
    return points, fields


def main():
    app, prm, workdir = sys.argv[1:4]
    hertz = read_hertz_line(prm)
    dim, R, P, E, nu = (int(hertz["dim"]), hertz["R"], hertz["P"], hertz["E"],
                        hertz["nu"])
    E_star = E / (1 - nu * nu)
    fraction = 0.5 if dim == 2 else 0.25

    def closed_form(P):
        if dim == 2:
            a = math.sqrt(4 * P * R / (math.pi * E_star))
            return a, 2 * P / (math.pi * a)
        a = (3 * P * R / (4 * E_star)) ** (1 / 3)
        return a, 3 * P / (2 * math.pi * a * a)

    share = fraction * P

    shutil.rmtree(workdir, ignore_errors=True)
    os.makedirs(workdir)
    run = subprocess.run([app, os.path.abspath(prm)], cwd=workdir,
                         capture_output=True, text=True)
    print(run.stdout)
    if run.returncode != 0:
        print(run.stderr)
        sys.exit(f"dualcontact failed with exit code {run.returncode}")
    results = glob.glob(os.path.join(workdir, "**", "results.txt"),
                        recursive=True)
    folder = os.path.dirname(results[0])
    force = None
    applied = None
    with open(results[0]) as f:
        for line in f:
            if line.startswith("pair_1.normal_force"):
                force = float(line.split("=")[1])
            if line.startswith("body_1.applied_force"):
                applied = math.sqrt(sum(
                    float(v)**2 for v in line.split("=")[1].split(",")))
    # the load the discretized model carries (its loaded surface is
    # polygonal): the closed form for that load is the fair comparison
    a, p0 = closed_form(applied / fraction)
    a_nominal, p0_nominal = closed_form(P)
    points, fields = read_vtu(os.path.join(folder, "contact_1.vtu"))
    pressure, status = fields["pressure_Pa"], fields["status"]
    r = [math.hypot(p[0], p[1]) if dim == 3 else abs(p[0]) for p in points]
    r_in = max(ri for ri, s in zip(r, status) if s != 0)
    outside = [ri for ri, s in zip(r, status) if s == 0 and ri > r_in]
    r_out = min(outside) if outside else r_in
    a_h = 0.5 * (r_in + r_out)
    peak = max(pressure)

    checks = [
        ("total normal force / applied load - 1", force / applied - 1,
         1e-8),
        ("contact radius / a - 1", a_h / a - 1, 0.05),
        ("peak pressure / p0 - 1", peak / p0 - 1, 0.10),
    ]
    print(f"Hertz {dim}D: for P = {P:g}: a = {a_nominal:.6g} m, p0 = "
          f"{p0_nominal:.6g} Pa; for the applied load P = "
          f"{applied / fraction:.9g}: a = {a:.6g} m, p0 = {p0:.6g} Pa; "
          f"measured a_h = "
          f"{a_h:.6g} m (last contact node {r_in:.6g}, first separated "
          f"{r_out:.6g}), peak {peak:.6g} Pa, contact force {force:.12g}, "
          f"applied load {applied:.12g} (the model's share of P: "
          f"{share:.12g}; they differ where the discretized loaded surface "
          f"is not exactly the true one)")
    failed = False
    for what, value, limit in checks:
        ok = abs(value) <= limit
        failed |= not ok
        print(f"  {'ok  ' if ok else 'FAIL'} {what}: {value:.3e} "
              f"(limit {limit:g})")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
