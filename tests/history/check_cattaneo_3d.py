#!/usr/bin/python3
"""Cattaneo-Mindlin in 3D on a load history (tests/history/cattaneo_3d.prm:
the lower half of a ball on a block of its own material, Dundurs beta = 0).

Usage: check_cattaneo_3d.py DUALCONTACT INPUT.prm WORKDIR
                            [--peak S] [--final S'] [--mu MU] [--tolerance N]
                            [--plot PICTURE.png]

One history: the top pressed at t = 1 and held, moved along x by S at
t = 2 (two steps) and back to S' at t = 3 (two steps), set here through
--set.  P, Q* (t = 2) and Q (t = 3) are the run's normal and tangential
forces (history.csv).  On the contact surfaces of steps 3 (t = 2) and 5
(t = 3), contact_1_step_3.vtu and contact_1_step_5.vtu, with r the
distance of a node from the axis x = y = 0:
  - the stick radius c is measured twice: c_in, the largest r of the
    sticking nodes, and c_out, the smallest r of the nodes that slip
    (both in contact, status 1 and 2); the contact radius a =
    sqrt(contact area / pi) of the step (pair_1.contact_area), h the node
    spacing (the median distance of a contact node to its nearest);
  - at Q*: Cattaneo's c/a = (1 - Q*/(mu P))^(1/3), both c_in and c_out
    within N node spacings (default 1) of c;
  - after unloading to Q: the nodes that slip again lie outside
    c'/a = (1 - (Q* - Q)/(2 mu P))^(1/3), those inside stick: c_in and
    c_out within N spacings of c';
  - --plot draws both steps' contact nodes by status with the circles
    a and c (c') of the closed form (matplotlib; not part of the check);
  - every step's forces balance and P stays constant (1e-3 relative:
    beta = 0, the normal and tangential problems uncouple).
"""
import argparse
import math
import os
import shutil
import sys

import numpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "postprocess"))
sys.path.insert(0, os.path.join(HERE, ".."))
import contact_vtu  # noqa: E402
from script_tools import (  # noqa: E402
    check,
    exit_status,
    run_app,
    read_history)


def run(args):
    s = ("(t <= 1 ? 0 : (t <= 2 ? %.12g*(t - 1) : %.12g + %.12g*(t - 2)))"
         % (args.peak, args.peak, args.final - args.peak))
    return run_app(args.app, args.input, args.workdir, "history",
                   ["Output/Write VTU=true",
                    "Load steps/Step times=1, 1.5, 2, 2.5, 3",
                    "Body 1/Dirichlet 1/Displacement=" + s
                    + "; 0; -0.03*min(t, 1)"])


def zone(out, step):
    """(c_in, c_out, h): the largest radius of the stick nodes, the
    smallest of the slip nodes, the node spacing."""
    points, fields = contact_vtu.read_contact_nodes(
        os.path.join(out, "contact_1_step_%d.vtu" % step))
    r = numpy.hypot(points[:, 0], points[:, 1])
    stick = fields["status"] == 1
    slip = fields["status"] == 2
    pressed = points[stick | slip]
    c_in = r[stick].max() if stick.any() else 0.0
    c_out = r[slip].min() if slip.any() else math.inf
    nearest = [numpy.sort(numpy.linalg.norm(pressed - p, axis=1))[1]
               for p in pressed]
    return c_in, c_out, float(numpy.median(nearest))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("app")
    parser.add_argument("input")
    parser.add_argument("workdir")
    parser.add_argument("--peak", type=float, default=0.009)
    parser.add_argument("--final", type=float, default=0.002)
    parser.add_argument("--mu", type=float, default=0.3)
    parser.add_argument("--tolerance", type=float, default=1.0)
    parser.add_argument("--plot", help="draw the stick zones into this .png")
    args = parser.parse_args()
    args.app, args.input = (os.path.abspath(p) for p in (args.app, args.input))
    shutil.rmtree(args.workdir, ignore_errors=True)
    os.makedirs(args.workdir)
    out = run(args)
    if out is None:
        return 1
    rows = read_history(out)
    mu = args.mu
    P = rows[0]["pair_1.normal_force"]
    for row in rows:
        check(abs(row["pair_1.normal_force"] - P) <= 1e-3 * P,
              "t = %g: P constant (%.6g)" % (row["time"], P),
              row["pair_1.normal_force"])
        imbalance = max(row[k] for k in row if k.endswith("force_imbalance"))
        check(imbalance <= 1e-6 * P, "t = %g: forces balance" % row["time"],
              imbalance)
    # Hertz, two bodies of one material: E* = E / (2 (1 - nu^2)), R = 1
    E, nu, R = 1000.0, 0.3, 1.0
    print("info P = %.5g N, Hertz a = %.5f m" % (
        P, (3 * P * R * 2 * (1 - nu * nu) / (4 * E)) ** (1 / 3)))
    Qs, Q = (abs(rows[i]["pair_1.tangential_force.x"]) for i in (2, 4))
    cases = [("loaded to Q*/(mu P) = %.4f" % (Qs / (mu * P)), 3,
              (1 - Qs / (mu * P)) ** (1 / 3)),
             ("unloaded to Q/(mu P) = %.4f" % (Q / (mu * P)), 5,
              (1 - (Qs - Q) / (2 * mu * P)) ** (1 / 3))]
    if args.plot:
        plot(args.plot, out, rows, cases)
    for name, step, expected in cases:
        a = math.sqrt(rows[step - 1]["pair_1.contact_area"] / math.pi)
        c_in, c_out, h = zone(out, step)
        for which, c in (("c_in (largest stick r)", c_in),
                         ("c_out (smallest slip r)", c_out)):
            check(abs(c - expected * a) <= args.tolerance * h,
                  "%s: %s against c/a = %.4f" % (name, which, expected),
                  "c = %.5f, a = %.5f, c/a = %.4f, h = %.5f (%.2f spacings)"
                  % (c, a, c / a, h, abs(c - expected * a) / h))
    return exit_status()


def plot(path, out, rows, cases):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    figure, axes = plt.subplots(1, 2, figsize=(10, 5))
    for ax, (name, step, expected) in zip(axes, cases):
        points, fields = contact_vtu.read_contact_nodes(
            os.path.join(out, "contact_1_step_%d.vtu" % step))
        a = math.sqrt(rows[step - 1]["pair_1.contact_area"] / math.pi)
        for status, colour, label in ((0, "lightgrey", "separated"),
                                      (1, "tab:blue", "stick"),
                                      (2, "tab:red", "slip")):
            chosen = fields["status"] == status
            ax.plot(points[chosen, 0], points[chosen, 1], "o", ms=4,
                    color=colour, label=label)
        angle = numpy.linspace(0, 2 * math.pi, 200)
        for radius, style, label in ((a, "k-", "a"),
                                     (expected * a, "k--", "closed form")):
            ax.plot(radius * numpy.cos(angle), radius * numpy.sin(angle),
                    style, lw=1, label=label)
        ax.set_xlim(-1.4 * a, 1.4 * a)
        ax.set_ylim(-1.4 * a, 1.4 * a)
        ax.set_aspect("equal")
        ax.set_xlabel("x [m] (load direction)")
        ax.set_ylabel("y [m]")
        ax.set_title("t = %g: %s" % (rows[step - 1]["time"], name), fontsize=9)
    axes[0].legend(loc="upper right", fontsize=8)
    figure.suptitle("Cattaneo-Mindlin in 3D: %s"
                    % os.path.join(out, "contact_1_step_{3,5}.vtu"),
                    fontsize=9)
    figure.tight_layout()
    figure.savefig(path, dpi=120)


if __name__ == "__main__":
    sys.exit(main())
