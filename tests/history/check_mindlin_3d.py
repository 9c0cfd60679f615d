#!/usr/bin/env python3
"""Mindlin-Deresiewicz in 3D: the energy dissipated per fretting cycle
(tests/history/mindlin_3d.prm: the lower half of a ball on a block of its
own material, Dundurs beta = 0).

Usage: check_mindlin_3d.py DUALCONTACT INPUT.prm WORKDIR [--amplitude S]
                           [--indentation D] [--step DT] [--cycles N]
                           [--mu MU] [--E E]
                           [--nu NU] [--radius R] [--tolerance T]
                           [--cycle-tolerance T2] [--csv FILE]
                           [--set KEY=VALUE ...]

The top of the ball is pressed by D (default 7.5 mm) at t = 1 and held; its
tangential (x) displacement follows the triangle wave 0 (t = 1) -> S
(default 2.25 mm, t = 2) -> -S (t = 4) -> S (t = 6) ..., period 4, in steps of DT (default 1: two steps per half
cycle; the incremental problem of a monotone half cycle is Mindlin's
unloading in one step, so finer steps change the energy little), N cycles
(default 3).  From history.csv, with P the normal force, Q* the tangential
force at the turning points of the last cycle, x = Q*/(mu P) and a the
Hertz radius of P:
  - P constant over the history (1e-3 relative; beta = 0) and every step's
    forces balance (1e-6 of P);
  - the energy dissipated in cycle k (total.dissipated_energy at its end
    minus at its start) equal in cycles 2, 3, ... to T2 (default 1e-6,
    relative): the loop repeats (the first loading differs);
  - against Mindlin-Deresiewicz (Johnson, Contact Mechanics, 7.59; design.md
    "Load history"):
      W = 9 mu^2 P^2 S_c / (10 a) [1 - (1 - x)^(5/3)
                                   - (5 x / 6) (1 + (1 - x)^(2/3))],
    S_c = (2 - nu1)/G1 + (2 - nu2)/G2: the last cycle's W within T (default
    0.05, relative);
  - the loop area, the integral of Q dS over the last cycle (trapezoids over
    the steps), printed beside it (it equals the dissipated energy as the
    steps get finer).
--csv writes the last two cycles' (S, Q) rows for a plot.
"""
import argparse
import math
import os
import shutil
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, ".."))
from script_tools import (  # noqa: E402
    check,
    exit_status,
    run_app,
    read_history)


def triangle(t, amplitude):
    """The top's x displacement at t (the wave of the docstring)."""
    if t <= 1:
        return 0.0
    if t <= 2:
        return amplitude * (t - 1)
    return amplitude * (abs(t - 2 - 4 * math.floor((t - 2) / 4) - 2) - 1)


def mindlin_deresiewicz(mu, P, a, S, x):
    """Energy dissipated per cycle +-Q*, x = Q*/(mu P) [J]."""
    return (9 * mu * mu * P * P * S / (10 * a)
            * (1 - (1 - x) ** (5 / 3)
               - 5 * x / 6 * (1 + (1 - x) ** (2 / 3))))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("app")
    parser.add_argument("input")
    parser.add_argument("workdir")
    parser.add_argument("--amplitude", type=float, default=0.00225)
    parser.add_argument("--step", type=float, default=1.0)
    parser.add_argument("--cycles", type=int, default=3)
    parser.add_argument("--indentation", type=float, default=0.0075)
    parser.add_argument("--mu", type=float, default=0.3)
    parser.add_argument("--E", type=float, default=1000.0)
    parser.add_argument("--nu", type=float, default=0.3)
    parser.add_argument("--radius", type=float, default=1.0)
    parser.add_argument("--tolerance", type=float, default=0.05)
    parser.add_argument("--cycle-tolerance", type=float, default=1e-6)
    parser.add_argument("--csv")
    parser.add_argument("--set", action="append", default=[])
    args = parser.parse_args()
    args.app, args.input = (os.path.abspath(p) for p in (args.app, args.input))
    shutil.rmtree(args.workdir, ignore_errors=True)
    os.makedirs(args.workdir)

    end = 2 + 4 * args.cycles
    n = int(round((end - 1) / args.step))
    times = [1 + args.step * k for k in range(n + 1)]
    wave = ("%.12g*(t <= 1 ? 0 : (t <= 2 ? t - 1 : "
            "abs(t - 2 - 4*floor((t - 2)/4) - 2) - 1))" % args.amplitude)
    out = run_app(args.app, args.input, args.workdir, "cycles",
                  ["Output/Write VTU=false",
                   "Load steps/Step times=" +
                   ", ".join("%.12g" % t for t in times),
                   "Body 1/Dirichlet 1/Displacement=%s; 0; -%.12g*min(t, 1)"
                   % (wave, args.indentation)] + args.set)
    if out is None:
        return exit_status()
    rows = read_history(out)
    check(len(rows) == len(times), "history.csv: one row per step", len(rows))
    P = rows[0]["pair_1.normal_force"]
    drift = max(abs(r["pair_1.normal_force"] - P) for r in rows) / P
    check(drift <= 1e-3, "P constant over the history (relative)",
          "%.3e (P = %.6g N)" % (drift, P))
    imbalance = max(r[k] for r in rows for k in r
                    if k.endswith("force_imbalance"))
    check(imbalance <= 1e-6 * P, "every step: forces balance", imbalance)

    def row_at(t):
        return min(range(len(rows)), key=lambda i: abs(rows[i]["time"] - t))

    energy = [r["total.dissipated_energy"] for r in rows]
    starts = [row_at(2 + 4 * c) for c in range(args.cycles + 1)]
    cycles = [energy[starts[c + 1]] - energy[starts[c]]
              for c in range(args.cycles)]
    print("info energy dissipated per cycle [J]: " +
          ", ".join("%.6e" % w for w in cycles))
    for c in range(1, args.cycles - 1):
        check(abs(cycles[c + 1] - cycles[c]) <= args.cycle_tolerance
              * abs(cycles[c]),
              "cycles %d and %d dissipate the same (relative)" % (c + 1, c + 2),
              "%.3e" % (abs(cycles[c + 1] - cycles[c]) / abs(cycles[c])))

    first, last = starts[-2], starts[-1]
    q = [r["pair_1.tangential_force.x"] for r in rows]
    s = [triangle(r["time"], args.amplitude) for r in rows]
    q_star = 0.5 * (abs(q[last]) + abs(q[row_at(4 + 4 * (args.cycles - 1))]))
    x = q_star / (args.mu * P)
    G = args.E / (2 * (1 + args.nu))
    compliance = 2 * (2 - args.nu) / G
    e_star = args.E / (2 * (1 - args.nu ** 2))
    a = (3 * P * args.radius / (4 * e_star)) ** (1 / 3)
    a_measured = math.sqrt(rows[last]["pair_1.contact_area"] / math.pi)
    expected = mindlin_deresiewicz(args.mu, P, a, compliance, x)
    area = sum(0.5 * (q[k] + q[k - 1]) * (s[k] - s[k - 1])
               for k in range(first + 1, last + 1))
    # the loop's area is the work of the top on the ball, the friction's
    # work the ball's and the block's: of opposite signs
    print("info P = %.6g N, Q* = %.6g N, x = Q*/(mu P) = %.4f, Hertz a = "
          "%.5f m (measured %.5f), stick radius c/a = %.4f"
          % (P, q_star, x, a, a_measured, (1 - x) ** (1 / 3)))
    print("info last cycle: loop area %.6e J (trapezoids over %d steps), "
          "dissipated %.6e J, Mindlin-Deresiewicz %.6e J"
          % (abs(area), last - first, cycles[-1], expected))
    error = (cycles[-1] - expected) / expected
    check(abs(error) <= args.tolerance,
          "energy per cycle against Mindlin-Deresiewicz within %g"
          % args.tolerance, "%+.4f" % error)
    if args.csv:
        with open(args.csv, "w") as f:
            f.write("time,displacement_x,tangential_force_x,"
                    "dissipated_energy\n")
            for k in range(starts[-3] if len(starts) > 2 else 0, last + 1):
                f.write("%.12g,%.12g,%.12g,%.12g\n"
                        % (rows[k]["time"], s[k], q[k], energy[k]))
    return exit_status()


if __name__ == "__main__":
    sys.exit(main())
