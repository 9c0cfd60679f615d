#!/usr/bin/env python3
"""The fretting loop of a load history: tangential force against the
tangential displacement, from history.csv (inputs/fretting.prm).

Usage: plot_fretting.py HISTORY.csv --amplitude A [--press-time T0]
                        [--force KEY] [--output PICTURE.png]

The displacement is the input's triangle wave: 0 up to T0 (default 1, the
press), then 0 -> A over T0 .. T0 + 1, A -> -A over the next 2, -A -> A
over the 2 after, and so on (`Displacement' of inputs/fretting.prm).  The
force is the column KEY (default pair_1.tangential_force.x, the force the
slave's surface takes along x).  Prints per full cycle (-A -> A -> -A or
A -> -A -> A, whatever the history holds) the loop's area, the work
integral of Q over the displacement (trapezoids over the steps), beside the
increase of total.dissipated_energy over the same steps: both are the
energy dissipated by friction per cycle.  Draws the loop into PICTURE.png
if given (matplotlib).
"""
import argparse
import csv
import math
import sys


def displacement(t, amplitude, t0):
    if t <= t0:
        return 0.0
    if t <= t0 + 1:
        return amplitude * (t - t0)
    u = t - t0 - 1
    return amplitude * (abs(u - 4 * math.floor(u / 4) - 2) - 1)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("history")
    parser.add_argument("--output", dest="picture")
    parser.add_argument("--amplitude", type=float, required=True)
    parser.add_argument("--press-time", type=float, default=1.0)
    parser.add_argument("--force", default="pair_1.tangential_force.x")
    args = parser.parse_args()
    with open(args.history) as f:
        rows = list(csv.DictReader(f))
    times = [float(r["time"]) for r in rows]
    q = [float(r[args.force]) for r in rows]
    d = [displacement(t, args.amplitude, args.press_time) for t in times]
    energy = [float(r.get("total.dissipated_energy", "nan")) for r in rows]
    # a full cycle: the steps from t0 + 1 (first +A) to t0 + 5
    start = args.press_time + 1
    for cycle in range(int((times[-1] - start) // 4 + 1e-9)):
        a, b = start + 4 * cycle, start + 4 * (cycle + 1)
        ks = [k for k, t in enumerate(times) if a - 1e-9 <= t <= b + 1e-9]
        if len(ks) < 3:
            continue
        work = sum(0.5 * (q[k] + q[k + 1]) * (d[k + 1] - d[k])
                   for k in ks[:-1])
        print("cycle %d (t = %g .. %g): loop area %.6e J, dissipated energy "
              "%.6e J" % (cycle + 1, a, b, abs(work),
                          energy[ks[-1]] - energy[ks[0]]))
    if args.picture:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        figure, axes = plt.subplots(figsize=(6, 4.5))
        axes.plot([1e6 * x for x in d], q, "o-", markersize=3)
        axes.set_xlabel("tangential displacement of the top [um]")
        axes.set_ylabel(args.force + " [N]")
        axes.set_title("Fretting loop (" + args.history + ")", fontsize=9)
        axes.grid(True, alpha=0.3)
        figure.tight_layout()
        figure.savefig(args.picture, dpi=120)
        print("wrote " + args.picture)
    return 0


if __name__ == "__main__":
    sys.exit(main())
