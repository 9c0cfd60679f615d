#!/usr/bin/env python3
"""Path dependence of friction on the slip increment (Mindlin-Deresiewicz).

Usage: check_path.py DUALCONTACT INPUT.prm WORKDIR --times T1,...,1
                     [--max-history-slip N] [--min-static-slip M]
                     [--set KEY=VALUE ...]

INPUT has its normal and tangential loads proportional to t with Q/P < mu
(tests/history/cattaneo_2d.prm).  Raised in the steps T1, ..., 1 no node
slips after the first step (itself a one-step loading of its small contact
zone) but for at most N (default 2: the outermost node on each side, which
enters the contact zone at its edge, where mu p -> 0, in the step it is
reached) in every step; the one step at t = 1 of the same loads shows
Cattaneo's partial slip, at least M (default 4) slipping nodes and some
sticking ones.  Both carry the same tangential force (the load) to 1e-8
and normal force (the reaction to the indentation) to 1e-4,
and the history dissipates (almost) nothing: total.dissipated_energy below
1e-3 of Q times the largest tangential displacement of the static run
(its slip is of that order); every step's forces balance
(force_imbalance <= 1e-8).
"""
import argparse
import csv
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


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("app")
    parser.add_argument("input")
    parser.add_argument("workdir")
    parser.add_argument("--times", required=True)
    parser.add_argument("--max-history-slip", type=int, default=2)
    parser.add_argument("--min-static-slip", type=int, default=4)
    parser.add_argument("--set", action="append", default=[])
    args = parser.parse_args()
    args.app, args.input = (os.path.abspath(p) for p in (args.app, args.input))
    shutil.rmtree(args.workdir, ignore_errors=True)
    os.makedirs(args.workdir)

    history = run_steps(args, "history", args.times)
    static = run_steps(args, "static", "1")
    if history is None or static is None:
        return 1
    with open(os.path.join(history, "history.csv")) as f:
        rows = list(csv.DictReader(f))
    slips = [int(r["pair_1.n_slip"]) for r in rows]
    sticks = [int(r["pair_1.n_stick"]) for r in rows]
    check(max(slips[1:]) <= args.max_history_slip,
          "history: slipping nodes per step after the first <= %d"
          % args.max_history_slip, list(zip(sticks, slips)))
    one = read_results(os.path.join(static, "results.txt"))
    last = read_results(os.path.join(history, "results.txt"))
    n_slip, n_stick = one["pair_1.n_slip"][0], one["pair_1.n_stick"][0]
    check(n_slip >= args.min_static_slip and n_stick > 0,
          "one step: partial slip (stick, slip)", (n_stick, n_slip))
    # the tangential force is the load; the normal force the reaction to the
    # prescribed indentation, which the path changes a little only
    for key, tolerance in (("pair_1.normal_force", 1e-4),
                           ("pair_1.tangential_force", 1e-8)):
        a, b = one[key], last[key]
        scale = max(abs(x) for x in a)
        difference = max(abs(x - y) for x, y in zip(a, b))
        check(difference <= tolerance * scale,
              key + ": history = one step to %g" % tolerance,
              "%.3e of %.6e" % (difference, scale))
    q = abs(one["pair_1.tangential_force"][0])
    reach = one["body_1.max_displacement"][0]
    dissipated = last["total.dissipated_energy"][0]
    check(abs(dissipated) <= 1e-3 * q * reach,
          "history: dissipated energy <= 1e-3 Q |u|max",
          "%.3e (Q |u|max = %.3e)" % (dissipated, q * reach))
    check_every_step_balances(rows)
    return exit_status()


if __name__ == "__main__":
    sys.exit(main())
