#!/usr/bin/env python3
"""A load history on one process against the same on N processes.

Usage: compare_processes.py DUALCONTACT INPUT.prm WORKDIR --times T1,...
                            --np N [--mpirun MPIRUN] [--set KEY=VALUE ...]
                            [--tolerance T]

Both runs must exit 0; every value of every row of their history.csv
(forces, counts, areas, energies, displacements, dissipated energy; not the
round-off sized force imbalances) agrees to T (default 1e-8) relative to
its own size (absolutely below 1e-12).  With `--set Dual problem/QP
vectors=distributed' the QPs, their warm starts and the per-step linear
terms run on distributed vectors.
"""
import argparse
import csv
import os
import shutil
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, ".."))
from script_tools import (  # noqa: E402
    check, exit_status, mpi_launcher, run_app)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("app")
    parser.add_argument("input")
    parser.add_argument("workdir")
    parser.add_argument("--times", required=True)
    parser.add_argument("--np", type=int, default=2)
    parser.add_argument("--mpirun", default="mpirun")
    parser.add_argument("--set", action="append", default=[])
    parser.add_argument("--tolerance", type=float, default=1e-8)
    args = parser.parse_args()
    args.app, args.input = (os.path.abspath(p) for p in (args.app, args.input))
    shutil.rmtree(args.workdir, ignore_errors=True)
    os.makedirs(args.workdir)
    tables = []
    for np in (1, args.np):
        launcher = mpi_launcher(args.mpirun, np)
        out = run_app(args.app, args.input, args.workdir, "np%d" % np,
                      ["Output/Write VTU=false",
                       "Load steps/Step times=" + args.times] + args.set,
                      launcher=launcher, label="%d process(es)" % np)
        if out is None:
            return 1
        with open(os.path.join(out, "history.csv")) as f:
            tables.append(list(csv.DictReader(f)))
    one, many = tables
    check(len(one) == len(many) == len(args.times.split(",")),
          "one row per step in both", (len(one), len(many)))
    worst, worst_key = 0.0, "-"
    for a, b in zip(one, many):
        for key in a:
            if "imbalance" in key:
                continue
            x, y = float(a[key]), float(b[key])
            d = abs(x - y) / abs(x) if abs(x) > 1e-12 else abs(x - y)
            if d > worst:
                worst, worst_key = d, "step %s %s" % (a["step"], key)
    check(worst <= args.tolerance, "1 against %d processes, every row"
          % args.np, "%.3e (%s)" % (worst, worst_key))
    return exit_status()


if __name__ == "__main__":
    sys.exit(main())
