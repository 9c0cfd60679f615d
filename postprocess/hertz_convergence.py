#!/usr/bin/python3
"""Hertz contact: errors of a dualcontact run against the closed form, and
convergence tables over a sequence of meshes (benchmark B3, issue 4).

Run with /usr/bin/python3 (Debian's numpy).  Used by scripts/bench_hertz (the
tables and doc/hertz.md) and by tests/hertz/check_hertz.py (the thresholds).

    hertz_convergence.py [--markdown FILE] [--command TEXT]
                         CASE:LEVEL:INPUT.prm:OUTPUT_FOLDER ...

Each argument names one finished run: a case name (rows with the same case
form one table), its refinement level, the .prm that was run (its first line
is the `# Hertz:' line) and the output folder it wrote.

The `# Hertz:' line: `# Hertz: dim = D, R = .., P = .., E = .., nu = ..'
and, for two elastic bodies, `R2 = .., E2 = .., nu2 = ..'.  P is the total
force on the full body (per metre of thickness in 2D); the inputs model a half
(2D, symmetry plane x = 0) or a quarter (3D, symmetry planes x = 0 and y = 0)
and so carry P/2 or P/4.  With 1/R* = 1/R + 1/R2 (1/R2 = 0 for a rigid plane)
and 1/E* = (1 - nu^2)/E + (1 - nu2^2)/E2 (0 for a rigid plane):
  2D (plane strain, cylinders): a = sqrt(4 P R* / (pi E*)), p0 = 2 P / (pi a)
  3D (spheres):                  a = (3 P R* / (4 E*))^(1/3), p0 = 3 P / (2 pi a^2)
and p(r) = p0 sqrt(1 - r^2/a^2) for r < a, 0 beyond, r the distance from the
axis of symmetry (|x| in 2D, sqrt(x^2 + y^2) in 3D, reference coordinates).

The closed form is evaluated for the nominal load P of the `# Hertz:' line
(the input's promise); the load the discretized model carries (the sum of the
bodies' applied forces in results.txt divided by the model's fraction) is
reported beside it (`applied'): the tractions on curved faces are integrated
on the true geometry (`Curved load mapping degree'), so the two agree to
round-off on the shipped inputs.

What is measured per run (from results.txt, statistics.json and the pair's
contact_1.vtu, which has per contact node the pressure p_i = lambda_N,i / w_i,
the area weight w_i = int phi_i ds and the status):
  force:  the resultant sum_i p_i w_i n_i of the nodal contact forces along
          the applied load, / applied load - 1 (for a rigid plane it is
          pair_1.normal_force; on a curved master the normals tilt and
          sum_i lambda_N,i exceeds the load by O((a/R)^2), see `force');
  a_h:    the contact half-width / radius with the edge located below the
          node spacing (lib/contact/contact_extent.h: p^2 extrapolated
          linearly across the edge): in 2D pair_1.contact_length of
          results.txt (the model is the half x >= 0, so the length is the
          half-width), in 3D sqrt(4 A / pi) from pair_1.contact_area A of the
          quarter model; error a_h / a - 1;
  a_nodes: the node-spacing estimate, the midpoint between the outermost
          node in contact and the nearest separated node beyond it (error
          a_nodes_error);
  peak:   max_i p_i / p0 - 1;
  load err: applied / (fraction P) - 1, the load the model carries against
          the nominal one;
  L2 nodal: sqrt(sum_i w_i (p_i - p(r_i))^2) / ||p||_L2, the quadrature
          whose nodes are the contact nodes and whose weights are the w_i.  It
          is the quadrature the method itself uses (the nodal force lambda_N,i
          is p_i w_i, and sum_i w_i p_i is the total force exactly), for Q1 it
          is the trapezoidal rule on each face (product trapezoidal in 3D);
          ||p||_L2 is the exact norm of the closed form over the modelled part
          of the contact zone (2D: p0^2 2a/3; 3D quarter: pi p0^2 a^2 / 8);
  L2 interp (2D only): the L2 error of the piecewise-linear interpolant of
          the nodal pressures along x, against p(x), integrated by 16-point
          Gauss-Legendre per segment (segments split at x = a, where p has
          its square-root singularity), relative to the same exact norm.
"""
import glob
import json
import math
import os
import re
import sys
import numpy

import contact_vtu


def read_hertz_line(path):
    """The values of the `# Hertz:' first line of PATH as a dict."""
    with open(path) as f:
        first = f.readline()
    m = re.match(r"#\s*Hertz:\s*(.*)", first)
    if not m:
        raise ValueError(f"{path}: the first line is not a `# Hertz:' line")
    values = {}
    for item in m.group(1).split(","):
        key, value = item.split("=")
        values[key.strip()] = float(value)
    for key in ("dim", "R", "P", "E", "nu"):
        if key not in values:
            raise ValueError(f"{path}: the `# Hertz:' line has no `{key} ='")
    two = [k for k in ("R2", "E2", "nu2") if k in values]
    if two and len(two) != 3:
        raise ValueError(f"{path}: give all of R2, E2, nu2 or none")
    return values


class ClosedForm:
    """Hertz's half-space solution for the line's data."""

    def __init__(self, hertz):
        self.dim = int(hertz["dim"])
        self.two_bodies = "R2" in hertz
        inverse_R = 1 / hertz["R"]
        inverse_E = (1 - hertz["nu"] ** 2) / hertz["E"]
        if self.two_bodies:
            inverse_R += 1 / hertz["R2"]
            inverse_E += (1 - hertz["nu2"] ** 2) / hertz["E2"]
        self.R_star = 1 / inverse_R
        self.E_star = 1 / inverse_E
        self.P = hertz["P"]
        self.fraction = 0.5 if self.dim == 2 else 0.25

    def a_p0(self, P):
        """Contact half-width / radius and peak pressure for the force P."""
        if self.dim == 2:
            a = math.sqrt(4 * P * self.R_star / (math.pi * self.E_star))
            return a, 2 * P / (math.pi * a)
        a = (3 * P * self.R_star / (4 * self.E_star)) ** (1 / 3)
        return a, 3 * P / (2 * math.pi * a * a)

    def l2_norm(self, a, p0):
        """||p||_L2 over the modelled part of the contact zone."""
        if self.dim == 2:
            return p0 * math.sqrt(2 * a / 3)
        return p0 * a * math.sqrt(math.pi / 8)


def read_results(path):
    """results.txt as {key: [floats]}."""
    values = {}
    with open(path) as f:
        for line in f:
            if "=" in line and not line.startswith("#"):
                key, value = line.split("=", 1)
                values[key.strip()] = [float(v) for v in value.split(",")]
    return values


def output_folder(workdir):
    """The folder holding results.txt under WORKDIR (or WORKDIR itself)."""
    if os.path.exists(os.path.join(workdir, "results.txt")):
        return workdir
    found = glob.glob(os.path.join(workdir, "**", "results.txt"),
                      recursive=True)
    if len(found) != 1:
        raise ValueError(f"{workdir}: expected one results.txt, found "
                         f"{len(found)}")
    return os.path.dirname(found[0])


def interpolant_l2(x, p, a, p0):
    """2D: || I_h p_h - p ||_L2(0, max x) of the piecewise-linear interpolant
    of the nodal values (x sorted), 16-point Gauss per piece, the piece that
    holds x = a split there."""
    gx, gw = numpy.polynomial.legendre.leggauss(16)
    total = 0.0
    for k in range(len(x) - 1):
        pieces = [(x[k], x[k + 1])]
        if x[k] < a < x[k + 1]:
            pieces = [(x[k], a), (a, x[k + 1])]
        for lo, hi in pieces:
            if hi <= lo:
                continue
            s = 0.5 * (hi - lo) * gx + 0.5 * (hi + lo)
            ph = p[k] + (p[k + 1] - p[k]) * (s - x[k]) / (x[k + 1] - x[k])
            exact = p0 * numpy.sqrt(numpy.clip(1 - (s / a) ** 2, 0, None))
            total += 0.5 * (hi - lo) * numpy.sum(gw * (ph - exact) ** 2)
    return math.sqrt(total)


def evaluate(prm, workdir):
    """Errors of the run of PRM whose output is under WORKDIR (a dict)."""
    closed = ClosedForm(read_hertz_line(prm))
    folder = output_folder(workdir)
    results = read_results(os.path.join(folder, "results.txt"))
    with open(os.path.join(folder, "statistics.json")) as f:
        statistics = json.load(f)
    if results.get("contact.converged", [0])[0] != 1:
        raise ValueError(f"{folder}: the contact solver did not converge")
    n_bodies = int(results["n_bodies"][0])
    applied = sum(math.sqrt(sum(v * v for v in
                                results[f"body_{b}.applied_force"]))
                  for b in range(1, n_bodies + 1))
    force = results["pair_1.normal_force"][0]
    a, p0 = closed.a_p0(closed.P)

    points, fields = contact_vtu.read_contact_nodes(
        os.path.join(folder, "contact_1.vtu"))
    if "area_weight_m2" not in fields:
        raise ValueError(f"{folder}/contact_1.vtu has no `area_weight_m2' "
                         "field")
    pressure, status, weight = (fields["pressure_Pa"], fields["status"],
                                fields["area_weight_m2"])
    if closed.dim == 2:
        r = numpy.abs(points[:, 0])
    else:
        r = numpy.hypot(points[:, 0], points[:, 1])
    # The resultant of the contact forces lambda_N,i n_i (the force the slave
    # exerts on the master) along the applied load.  pair_1.normal_force of
    # results.txt is sum_i lambda_N,i, each along its own normal: on a curved
    # master (two bodies) the normals tilt by about x/R2 and that sum exceeds
    # the load by O((a/R)^2); the resultant is what equilibrium fixes.
    load = numpy.zeros(3)
    for b in range(1, n_bodies + 1):
        vector = results[f"body_{b}.applied_force"]
        load[:len(vector)] += vector
    direction = load / numpy.linalg.norm(load)
    resultant = float(numpy.sum((pressure * weight)[:, None]
                                * fields["normal"], axis=0) @ direction)
    touching = status != 0
    if not touching.any():
        raise ValueError(f"{folder}: no contact node is in contact")
    r_in = r[touching].max()
    beyond = r[(~touching) & (r > r_in)]
    r_out = beyond.min() if beyond.size else r_in
    a_nodes = 0.5 * (r_in + r_out)
    if closed.dim == 2:
        a_h = results["pair_1.contact_length"][0]
    else:
        a_h = math.sqrt(results["pair_1.contact_area"][0] / (math.pi / 4))
    exact = p0 * numpy.sqrt(numpy.clip(1 - (r / a) ** 2, 0, None))
    norm = closed.l2_norm(a, p0)
    row = {
        "dim": closed.dim,
        "two_bodies": closed.two_bodies,
        "a": a,
        "p0": p0,
        "a_nominal": closed.a_p0(closed.P)[0],
        "p0_nominal": closed.a_p0(closed.P)[1],
        "applied": applied,
        "share": closed.fraction * closed.P,
        "force": force,
        "force_resultant": resultant,
        "force_error": resultant / applied - 1,
        "a_h": a_h,
        "r_in": r_in,
        "r_out": r_out,
        # the node spacing at the centre of the contact zone: the distance of
        # the nearest node to the node on the axis (the meshes are uniform
        # there, refined locally towards the contact point)
        "h": r[r > 1e-9 * a].min(),
        "a_error": a_h / a - 1,
        "a_nodes": a_nodes,
        "a_nodes_error": a_nodes / a - 1,
        "applied_error": applied / (closed.fraction * closed.P) - 1,
        "peak": pressure.max(),
        "peak_error": pressure.max() / p0 - 1,
        "l2_nodal": math.sqrt(numpy.sum(weight * (pressure - exact) ** 2))
        / norm,
        "n_contact": int(touching.sum()),
        "n_nodes": len(r),
        "n_dofs": sum(b["n_dofs"] for b in statistics["bodies"]),
        "wall_time": sum(statistics["wall_time_s"].values()),
        "qp_time": statistics["contact"]["qp_wall_time_s"],
        "hessian_products": sum(q["hessian_products"] for q in
                                statistics["contact"]["qp_solves"]),
    }
    if closed.dim == 2:
        order = numpy.argsort(r)
        row["l2_interp"] = interpolant_l2(r[order], pressure[order], a,
                                          p0) / norm
    return row


def rate(e_coarse, e_fine, h_coarse, h_fine):
    if e_coarse == 0 or e_fine == 0 or h_coarse == h_fine:
        return float("nan")
    return math.log(abs(e_coarse / e_fine)) / math.log(h_coarse / h_fine)


def table(rows):
    """Markdown table of one case's rows (sorted by level), with rates
    (observed orders in the contact-edge node spacing h)."""
    dim = rows[0][1]["dim"]
    columns = ["level", "dofs", "in contact", "h [m]", "a_h [m]",
               "err a", "rate", "err a (nodes)", "err p0", "rate",
               "L2 nodal", "rate"]
    if dim == 2:
        columns += ["L2 interp", "rate"]
    columns += ["load err", "force err", "QP products", "time [s]"]
    lines = ["| " + " | ".join(columns) + " |",
             "|" + "---|" * len(columns)]
    previous = None
    for level, row in rows:
        def r(key):
            if previous is None:
                return "-"
            return f"{rate(previous[key], row[key], previous['h'], row['h']):.2f}"
        cells = [str(level), str(row["n_dofs"]), str(row["n_contact"]),
                 f"{row['h']:.3g}", f"{row['a_h']:.5g}",
                 f"{row['a_error']:+.2e}", r("a_error"),
                 f"{row['a_nodes_error']:+.2e}",
                 f"{row['peak_error']:+.2e}", r("peak_error"),
                 f"{row['l2_nodal']:.2e}", r("l2_nodal")]
        if dim == 2:
            cells += [f"{row['l2_interp']:.2e}", r("l2_interp")]
        cells += [f"{row['applied_error']:+.1e}",
                  f"{row['force_error']:+.1e}", str(row["hessian_products"]),
                  f"{row['wall_time']:.2f}"]
        lines.append("| " + " | ".join(cells) + " |")
        previous = row
    return "\n".join(lines)


def main(argv):
    markdown = None
    command = None
    runs = []
    args = list(argv)
    while args:
        arg = args.pop(0)
        if arg == "--markdown":
            markdown = args.pop(0)
        elif arg == "--command":
            command = args.pop(0)
        else:
            case, level, prm, workdir = arg.split(":", 3)
            runs.append((case, int(level), prm, workdir))
    if not runs:
        sys.exit(__doc__)
    cases = {}
    for case, level, prm, workdir in runs:
        cases.setdefault(case, (prm, []))[1].append((level,
                                                     evaluate(prm, workdir)))
    text = []
    for case, (prm, rows) in cases.items():
        rows.sort(key=lambda lr: lr[0])
        first = rows[0][1]
        with open(prm) as f:
            hertz = f.readline().strip()
        text.append(f"### {case}\n\n`{hertz}`\n\n"
                    f"Closed form for the nominal load: a = {first['a']:.5g} "
                    f"m, p0 = {first['p0']:.5g} Pa.\n\n" + table(rows) + "\n")
    output = "\n".join(text)
    print(output)
    if markdown:
        with open(markdown) as f:
            document = f.read()
        begin, end = "<!-- tables begin -->", "<!-- tables end -->"
        if begin not in document or end not in document:
            sys.exit(f"{markdown}: no `{begin}' ... `{end}' section")
        head = document.split(begin)[0]
        tail = document.split(end)[1]
        block = begin + "\n\n"
        if command:
            block += f"Produced by: {command}.\n\n"
        block += output + "\n" + end
        with open(markdown, "w") as f:
            f.write(head + block + tail)


if __name__ == "__main__":
    main(sys.argv[1:])
