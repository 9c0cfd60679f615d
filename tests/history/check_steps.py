#!/usr/bin/env python3
"""Runs a load history of dualcontact and compares its steps with static
runs of the same loads.

Usage: check_steps.py DUALCONTACT INPUT.prm WORKDIR --times T1,T2,...
                      [--rows all|first|last] [--set KEY=VALUE ...]
                      [--tolerance T] [--min-solves N]

The history (`Load steps/Step times = T1, T2, ...') writes history.csv, one
row per step.  For each compared step k (--rows all: every step, the
frictionless case; first: step 1 only, the frictional case: later steps
depend on the path; last: the last step only, a history with contact
refinement cycles, whose last cycle's meshes are refined from its last
step as the one-step run's from its one step) the one-step run at t_k
writes results.txt; every
column of the row that results.txt has (forces, counts, areas; a vector's
components KEY.x, KEY.y, KEY.z) agrees to T (default 1e-8) relative to the
size of its quantity (a vector's norm; a force's relative to the largest
force of the run, so that a force zero but for round-off compares to the
scene's forces).  Also asserted: the history's
results.txt is its last step's (the same forces as the last row), and
history.csv has one row per step with step and time.  With
--min-solves N both runs' results.txt say they solved at least N times
(`refinement.n_solves', one solve per refinement cycle).

The steps' normal forces must differ (the loads follow t).  Every run must
exit 0, and every step's forces balance (every body's
force_imbalance in history.csv <= 1e-8).
"""
import argparse
import csv
import math
import os
import shutil
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, ".."))
from script_tools import (  # noqa: E402
    check,
    exit_status,
    run_steps,
    read_results,
    check_every_step_balances)


def compare(row, static, label, tolerance):
    worst, worst_key, n = 0.0, "-", 0
    # a force is compared relative to the largest force of the run: a
    # reaction that is zero but for round-off (TFETI's, on a symmetry
    # plane: 4e-10 N beside a contact force of 1.5 N) has no size of its own
    largest_force = max((math.sqrt(sum(x * x for x in numbers))
                         for key, numbers in static.items()
                         if "force" in key and "imbalance" not in key),
                        default=0.0)
    for key, numbers in static.items():
        if "imbalance" in key:
            continue  # round-off sized: asserted below instead
        components = ([(key, numbers[0])] if len(numbers) == 1 else
                      [(key + "." + "xyz"[c], numbers[c])
                       for c in range(len(numbers))])
        if not all(k in row for k, _ in components):
            continue
        scale = math.sqrt(sum(x * x for x in numbers))
        if "force" in key:
            scale = max(scale, largest_force)
        difference = math.sqrt(sum((float(row[k]) - x) ** 2
                                   for k, x in components))
        relative = difference / scale if scale > 0 else difference
        n += 1
        if relative > worst:
            worst, worst_key = relative, key
    check(n > 5, label + ": quantities compared", n)
    check(worst <= tolerance, label + ": largest relative difference",
          "%.3e (%s)" % (worst, worst_key))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("app")
    parser.add_argument("input")
    parser.add_argument("workdir")
    parser.add_argument("--times", required=True)
    parser.add_argument("--rows", choices=("all", "first", "last"),
                        default="all")
    parser.add_argument("--min-solves", type=int, default=0)
    parser.add_argument("--set", action="append", default=[])
    parser.add_argument("--tolerance", type=float, default=1e-8)
    args = parser.parse_args()
    args.app, args.input = (os.path.abspath(p) for p in (args.app, args.input))
    shutil.rmtree(args.workdir, ignore_errors=True)
    os.makedirs(args.workdir)

    times = [t.strip() for t in args.times.split(",")]
    out = run_steps(args, "history", ", ".join(times))
    if out is None:
        return 1
    with open(os.path.join(out, "history.csv")) as f:
        rows = list(csv.DictReader(f))
    check(len(rows) == len(times), "history.csv: one row per step",
          len(rows))
    check(all(int(r["step"]) == k + 1 and
              abs(float(r["time"]) - float(times[k])) <= 1e-12
              for k, r in enumerate(rows)), "history.csv: step and time",
          [(r["step"], r["time"]) for r in rows])
    # the loads depend on t: the steps must differ (an expression that did
    # not see the step's time would give equal, even zero, steps that
    # trivially equal their one-step runs)
    if len(rows) > 1:
        spread = max(abs(float(r[key]) - float(rows[0][key]))
                     for r in rows for key in rows[0]
                     if key.endswith("normal_force"))
        check(spread > 1e-6 * max(abs(float(r[key])) for r in rows
                                  for key in rows[0]
                                  if key.endswith("normal_force")),
              "the steps' normal forces differ (the loads follow t)",
              "%.3e" % spread)
    compare(rows[-1], read_results(os.path.join(out, "results.txt")),
            "results.txt against the last row", 1e-9)
    steps = {"all": range(len(rows)), "first": [0],
             "last": [len(rows) - 1]}[args.rows]
    for k in steps:
        static = run_steps(args, "static_%d" % (k + 1), times[k])
        if static is None:
            continue
        results = read_results(os.path.join(static, "results.txt"))
        compare(rows[k], results,
                "step %d (t = %s) against one step at t = %s"
                % (k + 1, times[k], times[k]), args.tolerance)
        if args.min_solves > 0:
            solves = [read_results(os.path.join(folder, "results.txt"))
                      .get("refinement.n_solves", [0])[0]
                      for folder in (out, static)]
            check(min(solves) >= args.min_solves,
                  "refinement.n_solves of the history and the one step",
                  solves)
    check_every_step_balances(rows)
    return exit_status()


if __name__ == "__main__":
    sys.exit(main())
