#!/usr/bin/python3
"""Runs a Hertz input of dualcontact and compares it with the closed form.

Usage: check_hertz.py DUALCONTACT INPUT.prm WORKDIR [--l2 LIMIT]
                      [--radius LIMIT] [--peak LIMIT] [--load LIMIT]
                      [--set PATH=VALUE ...]

INPUT.prm starts with `# Hertz: dim = D, R = .., P = .., E = .., nu = ..'
(and `R2 = .., E2 = .., nu2 = ..' for two elastic bodies): see
postprocess/hertz_convergence.py for the closed forms (effective radius and
modulus for two bodies) and for how every error is measured.  The closed
form is evaluated for the nominal load P of the `# Hertz:' line; the load the
model carries (the bodies' applied forces in results.txt) is printed beside
it.

Asserted: the applied load equals the nominal share of P to --load (default
1e-6) relative (the loads on curved faces follow the true geometry); the
total normal contact force (the resultant of the nodal contact forces
p_i w_i n_i of contact_1.vtu along the load; for a rigid plane
pair_1.normal_force) equals the applied load to 1e-8 relative; the contact
radius / half-width (the edge located below the node spacing, results.txt
pair_1.contact_length / contact_area) within --radius (default 0.5 %) of a;
the peak nodal pressure within --peak (default 0.5 %) of p0; and, with
--l2, the relative L2 error of the nodal pressures (nodal quadrature with
the area weights w_i) below that limit.  The limits
of each input are justified by the convergence tables of doc/hertz.md
(scripts/bench_hertz).  --set passes a parameter change to dualcontact
(e.g. `Body 1/Mesh/Cell type=simplex`; repeatable).  Prints the measured
errors.
"""
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                "..", "..", "postprocess"))
import hertz_convergence  # noqa: E402


def main(argv):
    if len(argv) < 3:
        sys.exit(__doc__)
    app, prm, workdir = argv[:3]
    limits = {"--radius": 0.005, "--peak": 0.005, "--load": 1e-6,
              "--l2": None}
    options = argv[3:]
    settings = []
    while options:
        key = options.pop(0)
        if key == "--set" and options:
            settings += ["--set", options.pop(0)]
            continue
        if key not in limits or not options:
            sys.exit(f"unknown option or missing value: {key}\n{__doc__}")
        limits[key] = float(options.pop(0))

    shutil.rmtree(workdir, ignore_errors=True)
    os.makedirs(workdir)
    run = subprocess.run([app, os.path.abspath(prm)] + settings, cwd=workdir,
                         capture_output=True, text=True)
    print(run.stdout)
    if run.returncode != 0:
        print(run.stderr)
        sys.exit(f"dualcontact failed with exit code {run.returncode}")
    row = hertz_convergence.evaluate(prm, workdir)

    print(f"Hertz {row['dim']}D{' two bodies' if row['two_bodies'] else ''}: "
          f"for the nominal load P: a = {row['a']:.6g} m, "
          f"p0 = {row['p0']:.6g} Pa; applied resultant {row['applied']:.12g} "
          f"(nominal share {row['share']:.12g}, difference "
          f"{row['applied_error']:+.2e}); measured a_h = {row['a_h']:.6g} m "
          f"(node estimate {row['a_nodes']:.6g}: last contact node "
          f"{row['r_in']:.6g}, first separated {row['r_out']:.6g}), peak {row['peak']:.6g} Pa, contact force "
          f"resultant {row['force_resultant']:.12g} (sum of lambda_N "
          f"{row['force']:.12g}), node spacing h = {row['h']:.4g} m, "
          f"{row['n_contact']} of {row['n_nodes']} nodes in contact, "
          f"L2 (nodal quadrature) {row['l2_nodal']:.4e}"
          + (f", L2 (interpolant) {row['l2_interp']:.4e}"
             if 'l2_interp' in row else ""))
    checks = [
        ("applied load / nominal share of P - 1", row["applied_error"],
         limits["--load"]),
        ("total normal force / applied load - 1", row["force_error"], 1e-8),
        ("contact radius / a - 1", row["a_error"], limits["--radius"]),
        ("peak pressure / p0 - 1", row["peak_error"], limits["--peak"]),
    ]
    if limits["--l2"] is not None:
        checks.append(("relative pressure L2 error (nodal quadrature)",
                       row["l2_nodal"], limits["--l2"]))
    failed = False
    for what, value, limit in checks:
        ok = abs(value) <= limit
        failed |= not ok
        print(f"  {'ok  ' if ok else 'FAIL'} {what}: {value:.3e} "
              f"(limit {limit:g})")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main(sys.argv[1:])
