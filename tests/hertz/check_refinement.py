#!/usr/bin/python3
"""Contact-zone refinement on a Hertz input: it refines only near the
contact zone, and after its cycles the Hertz errors are below those of a
uniformly refined mesh with at least as many dofs.

Usage: check_refinement.py DUALCONTACT INPUT.prm WORKDIR --cycles N
           --uniform K --zone Z [--errors NAME,NAME,...]

INPUT.prm is a Hertz input (`# Hertz:' first line, see
postprocess/hertz_convergence.py) with a `Contact refinement' subsection.
Two runs: `Cycles = N' (adaptive), and `Cycles = 0' with every body's
`Global refinements' + K (uniform).  Asserted:
  - the adaptive run did N refinements (statistics.json, one record per
    solve) and every cycle refined some cells;
  - every cell the contact-zone criteria refine (nodes in contact or
    within the gap threshold, the zone factor; not the error indicator's
    cells, which go where the displacement's gradient jumps) lies within
    Z * a of the contact point (the origin; the bounding boxes of
    statistics.json `zone_cells_box_by_body'), a the closed-form contact
    half-width / radius, and every cycle refines some;
  - the uniform run has at least as many dofs as the adaptive one;
  - for each error of --errors (default a_error,l2_nodal; names of
    hertz_convergence.evaluate: a_error, peak_error, l2_nodal, l2_interp)
    |adaptive| < |uniform|;
  - the total contact force of the adaptive run equals the applied load to
    1e-8 relative.
Prints the measured values.
"""
import json
import math
import os
import re
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                "..", "..", "postprocess"))
import hertz_convergence  # noqa: E402


def run(app, text, workdir):
    shutil.rmtree(workdir, ignore_errors=True)
    os.makedirs(workdir)
    prm = os.path.join(workdir, "input.prm")
    with open(prm, "w") as f:
        f.write(text)
    result = subprocess.run([app, "input.prm"], cwd=workdir,
                            capture_output=True, text=True)
    print(result.stdout)
    if result.returncode != 0:
        print(result.stderr)
        sys.exit(f"dualcontact failed with exit code {result.returncode}")
    return prm


def main(argv):
    if len(argv) < 3:
        sys.exit(__doc__)
    app, prm, workdir = argv[:3]
    options = {"--cycles": None, "--uniform": None, "--zone": None,
               "--errors": "a_error,l2_nodal"}
    rest = argv[3:]
    while rest:
        key = rest.pop(0)
        if key not in options or not rest:
            sys.exit(f"unknown option or missing value: {key}\n{__doc__}")
        options[key] = rest.pop(0)
    if None in options.values():
        sys.exit(__doc__)
    cycles, levels = int(options["--cycles"]), int(options["--uniform"])
    zone = float(options["--zone"])
    with open(prm) as f:
        text = f.read()
    text = re.sub(r"(?m)^(\s*set Output folder\s*=).*$",
                  r"\1 out\n  set Write VTU = false", text)
    if not re.search(r"(?m)^\s*set Cycles\s*=", text):
        sys.exit(f"{prm} has no `set Cycles' line")
    adaptive_text = re.sub(r"(?m)^(\s*set Cycles\s*=\s*)\d+",
                           rf"\g<1>{cycles}", text)
    uniform_text = re.sub(r"(?m)^(\s*set Cycles\s*=\s*)\d+", r"\g<1>0", text)
    uniform_text = re.sub(
        r"(?m)^(\s*set Global refinements\s*=\s*)(\d+)",
        lambda m: m.group(1) + str(int(m.group(2)) + levels), uniform_text)

    adaptive_prm = run(app, adaptive_text, os.path.join(workdir, "adaptive"))
    uniform_prm = run(app, uniform_text, os.path.join(workdir, "uniform"))
    adaptive = hertz_convergence.evaluate(adaptive_prm,
                                          os.path.join(workdir, "adaptive"))
    uniform = hertz_convergence.evaluate(uniform_prm,
                                         os.path.join(workdir, "uniform"))
    with open(os.path.join(hertz_convergence.output_folder(
            os.path.join(workdir, "adaptive")), "statistics.json")) as f:
        records = json.load(f)["refinement"]["cycles"]

    checks = []
    checks.append((f"solves recorded (cycles + 1 = {cycles + 1})",
                   len(records), len(records) == cycles + 1))
    marked = [(r["n_zone_cells"], r["n_marked_cells"]) for r in records[:-1]]
    checks.append(("cells refined per cycle: (zone, all) all > 0", marked,
                   all(m[0] > 0 for m in marked)))
    reach = 0.0
    for r in records[:-1]:
        for box in r["zone_cells_box_by_body"]:
            if box is None:
                continue
            # the farthest corner of the box from the contact point (origin)
            far = [max(abs(lo), abs(hi)) for lo, hi in
                   zip(box["lower"], box["upper"])]
            reach = max(reach, math.sqrt(sum(x * x for x in far)))
    checks.append((f"farthest zone-refined point / a (limit {zone:g})",
                   reach / adaptive["a"], reach <= zone * adaptive["a"]))
    checks.append(("dofs: uniform >= adaptive",
                   f"{uniform['n_dofs']} >= {adaptive['n_dofs']}",
                   uniform["n_dofs"] >= adaptive["n_dofs"]))
    for name in options["--errors"].split(","):
        checks.append((f"|{name}|: adaptive < uniform",
                       f"{abs(adaptive[name]):.3e} < {abs(uniform[name]):.3e}",
                       abs(adaptive[name]) < abs(uniform[name])))
    checks.append(("adaptive total force / load - 1 (limit 1e-8)",
                   f"{adaptive['force_error']:.2e}",
                   abs(adaptive["force_error"]) <= 1e-8))
    print(f"a = {adaptive['a']:.6g} m, p0 = {adaptive['p0']:.6g} Pa")
    for kind, row in (("adaptive", adaptive), ("uniform", uniform)):
        print(f"{kind}: {row['n_dofs']} dofs, h = {row['h']:.4g} m, "
              f"{row['n_contact']} of {row['n_nodes']} nodes in contact, "
              f"err a {row['a_error']:+.3e}, err p0 {row['peak_error']:+.3e}, "
              f"L2 nodal {row['l2_nodal']:.3e}"
              + (f", L2 interp {row['l2_interp']:.3e}"
                 if "l2_interp" in row else "")
              + f", {row['wall_time']:.2f} s")
    failed = False
    for what, value, ok in checks:
        failed |= not ok
        print(f"  {'ok  ' if ok else 'FAIL'} {what}: {value}")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main(sys.argv[1:])
