#!/usr/bin/env python3
"""A load history on the undecomposed dual against the same on TFETI.

Usage: compare_duals.py DUALCONTACT INPUT.prm WORKDIR --times T1,...
                        [--set KEY=VALUE ...]
                        [--tfeti-set KEY=VALUE ...] [--np N]
                        [--mpirun MPIRUN] [--tolerance T]
                        [--ignore SUFFIX ...]

Runs the history (`Load steps/Step times = T1, ...', the --set overrides)
with `Decomposition/Method = none' on one process, then with `Method =
tfeti' (and the --tfeti-set overrides: subdomains, mesh distribution) on N
processes (default 1).  Both must exit 0 with one row per step in
history.csv, and every value of every row (forces, counts, areas,
energies, displacements, the dissipated energy; not the round-off sized
force imbalances) must agree to T (default 1e-6) relative to the largest
magnitude of its column over the steps (a column that is zero throughout
absolutely to 1e-12).  The stick / slip counts are compared the same way,
so a count that differs by one fails.  The steps must differ (the loads
follow t) and the TFETI run must have decomposed the scene (results.txt:
contact.n_subdomains > 1).  --ignore SUFFIX leaves the columns ending in
SUFFIX out (a quantity known to differ for a reason the test is not
about, named where the test is registered).
"""
import argparse
import csv
import os
import shutil
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, ".."))
from script_tools import (  # noqa: E402
    check, exit_status, mpi_launcher, read_results, run_app)


def history(args, name, settings, np):
    launcher = mpi_launcher(args.mpirun, np)
    out = run_app(args.app, args.input, args.workdir, name,
                  ["Output/Write VTU=false",
                   "Load steps/Step times=" + args.times] + args.set +
                  settings, launcher=launcher,
                  label="%s on %d process(es)" % (name, np))
    if out is None:
        return None, None
    with open(os.path.join(out, "history.csv")) as f:
        rows = list(csv.DictReader(f))
    results = read_results(os.path.join(out, "results.txt"))
    return rows, results.get("contact.n_subdomains", [0])[0]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("app")
    parser.add_argument("input")
    parser.add_argument("workdir")
    parser.add_argument("--times", required=True)
    parser.add_argument("--set", action="append", default=[])
    parser.add_argument("--tfeti-set", action="append", default=[])
    parser.add_argument("--np", type=int, default=1)
    parser.add_argument("--mpirun", default="mpirun")
    parser.add_argument("--tolerance", type=float, default=1e-6)
    parser.add_argument("--ignore", action="append", default=[])
    args = parser.parse_args()
    args.app, args.input = (os.path.abspath(p) for p in (args.app, args.input))
    shutil.rmtree(args.workdir, ignore_errors=True)
    os.makedirs(args.workdir)
    one, _ = history(args, "undecomposed", ["Decomposition/Method=none"], 1)
    many, n_subdomains = history(args, "tfeti",
                               ["Decomposition/Method=tfeti"] +
                               args.tfeti_set, args.np)
    if one is None or many is None:
        return exit_status()
    n_steps = len(args.times.split(","))
    check(len(one) == len(many) == n_steps, "one row per step in both",
          (len(one), len(many), n_steps))
    check(n_subdomains > 1, "the second run decomposed (results.txt: "
          "contact.n_subdomains)", n_subdomains)
    keys = [k for k in one[0] if "imbalance" not in k and k != "step" and
            not any(k.endswith(suffix) for suffix in args.ignore)]
    check(set(keys) <= set(many[0]), "the same columns in both",
          sorted(set(keys) - set(many[0])))
    forces = [k for k in keys if k.endswith("normal_force")]
    spread = max((abs(float(r[k]) - float(one[0][k]))
                  for r in one for k in forces), default=0.0)
    check(spread > 0, "the steps' normal forces differ (the loads follow t)",
          "%.3e" % spread)
    worst, worst_key = 0.0, "-"
    for key in keys:
        if key not in many[0]:
            continue
        size = max(abs(float(r[key])) for r in one)
        for a, b in zip(one, many):
            d = abs(float(a[key]) - float(b[key]))
            d = d / size if size > 1e-12 else d
            if d > worst:
                worst, worst_key = d, "step %s %s" % (a["step"], key)
    check(worst <= args.tolerance,
          "undecomposed against TFETI on %d process(es), every row (%d "
          "columns, %d steps)" % (args.np, len(keys), n_steps),
          "%.3e (%s)" % (worst, worst_key))
    return exit_status()


if __name__ == "__main__":
    sys.exit(main())
