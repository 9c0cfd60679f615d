#!/usr/bin/env python3
"""Fretting cycles in 2D (tests/history/cattaneo_2d.prm): after the first
loading the tangential cycles +-Q* repeat exactly.

Usage: check_cycles.py DUALCONTACT INPUT.prm WORKDIR [--peak X]
                       [--cycles N] [--tolerance T]

The top is pressed at t = 1 and held (P from a run of the press alone);
the tangential load follows the triangle wave 0 -> Q* (t = 1 .. 2) -> -Q*
-> Q* with period 4 (Q* = X mu P, default X = 0.6), a quarter of the
amplitude per step, N cycles (default 3).  Asserted on history.csv:
  - cycles 2 and 3 (and later) equal at the same phase to T (default
    1e-6): strain energies, largest displacements, stick / slip counts, and
    the energy dissipated per step, relative to the largest of each;
  - the first loading (t = 1 .. 2) dissipates otherwise than the
    reloading through the same loads (t = 5 .. 6): per step by more than
    1e-3 of the largest step's (as it must: the path);
  - the energy dissipated per cycle is positive and the same in every
    cycle after the first.
"""
import argparse
import csv
import os
import shutil
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, ".."))
from script_tools import check, exit_status, run_steps  # noqa: E402


def run(args, name, times, traction):
    return run_steps(args, name, times,
                     ["Body 1/Traction 1/Traction=" + traction,
                      "Body 1/Dirichlet 1/Displacement=0; -6e-3*min(t, 1)"])


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("app")
    parser.add_argument("input")
    parser.add_argument("workdir")
    parser.add_argument("--peak", type=float, default=0.6)
    parser.add_argument("--mu", type=float, default=0.3)
    parser.add_argument("--cycles", type=int, default=3)
    parser.add_argument("--tolerance", type=float, default=1e-6)
    args = parser.parse_args()
    args.app, args.input = (os.path.abspath(p) for p in (args.app, args.input))
    shutil.rmtree(args.workdir, ignore_errors=True)
    os.makedirs(args.workdir)
    press = run(args, "press", "1", "0; 0")
    if press is None:
        return 1
    with open(os.path.join(press, "results.txt")) as f:
        P = [float(l.split("=")[1]) for l in f
             if l.startswith("pair_1.normal_force")][0]
    qs = args.peak * args.mu * P / 2
    traction = ("%.12g*(t <= 1 ? 0 : (t <= 2 ? t - 1 : "
                "abs(t - 2 - 4*floor((t - 2)/4) - 2) - 1)); 0" % qs)
    n_steps = 4 + 16 * args.cycles
    times = ", ".join("%g" % (1 + 0.25 * k) for k in range(n_steps + 1))
    out = run(args, "cycles", times, traction)
    if out is None:
        return 1
    with open(os.path.join(out, "history.csv")) as f:
        rows = list(csv.DictReader(f))
    check(len(rows) == n_steps + 1, "history.csv: one row per step", len(rows))
    energy = [float(r["total.dissipated_energy"]) for r in rows]
    per_step = [0.0] + [energy[k] - energy[k - 1] for k in range(1, len(rows))]
    keys = [k for k in rows[0] if k.endswith("strain_energy") or
            k.endswith("max_displacement") or k.endswith(".n_stick") or
            k.endswith(".n_slip")]
    columns = {k: [float(r[k]) for r in rows] for k in keys}
    columns["dissipated per step"] = per_step
    # row of t: 4 (t - 1); a cycle is 16 rows, cycle c starts at t = 2 + 4 c
    start = 4
    for c in range(1, args.cycles - 1):
        worst, worst_key = 0.0, "-"
        for key, values in columns.items():
            scale = max(abs(v) for v in values) or 1.0
            for k in range(16):
                a = values[start + 16 * c + k]
                b = values[start + 16 * (c + 1) + k]
                if abs(a - b) / scale > worst:
                    worst, worst_key = abs(a - b) / scale, key
        check(worst <= args.tolerance,
              "cycles %d and %d equal (relative to each quantity's largest)"
              % (c + 1, c + 2), "%.3e (%s)" % (worst, worst_key))
    # the first loading, t = 1 .. 2, against the reloading at the same
    # load, t = 5 .. 6 (rows 0..4 and 16..20)
    first = per_step[1:5]
    again = per_step[17:21]
    difference = max(abs(x - y) for x, y in zip(first, again)) / max(
        abs(v) for v in per_step)
    check(difference > 1e-3,
          "the first loading dissipates otherwise than the reloading",
          "%.3e (per step %s against %s)" % (difference, first, again))
    cycles = [energy[start + 16 * (c + 1)] - energy[start + 16 * c]
              for c in range(args.cycles)]
    check(all(w > 0 for w in cycles) and
          all(abs(w - cycles[1]) <= args.tolerance * cycles[1]
              for w in cycles[1:]),
          "energy dissipated per cycle (> 0, equal after the first)", cycles)
    return exit_status()


if __name__ == "__main__":
    sys.exit(main())
