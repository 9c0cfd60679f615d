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
import subprocess
import sys

failures = 0


def check(ok, what, value):
    global failures
    print(("ok   " if ok else "FAIL ") + what + ": " + str(value))
    if not ok:
        failures += 1


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
        out = os.path.join(args.workdir, "np%d" % np)
        command = [args.app, args.input, "--set", "Output/Output folder=" + out,
                   "--set", "Output/Write VTU=false",
                   "--set", "Load steps/Step times=" + args.times]
        for s in args.set:
            command += ["--set", s]
        if np > 1:
            command = [args.mpirun, "--allow-run-as-root", "--oversubscribe",
                       "-np", str(np)] + command
        result = subprocess.run(command, cwd=args.workdir,
                                capture_output=True, text=True)
        check(result.returncode == 0, "%d process(es): exit status" % np,
              result.returncode)
        if result.returncode != 0:
            print(" ".join(command))
            print(result.stdout[-3000:], result.stderr[-3000:])
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
    print("%d failure(s)" % failures)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
