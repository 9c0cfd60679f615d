#!/usr/bin/env python3
"""Cattaneo-Mindlin in 2D on a load history (tests/history/cattaneo_2d.prm:
a half disc on a block of its own material, Dundurs beta = 0).

Usage: check_cattaneo.py DUALCONTACT INPUT.prm WORKDIR
                         [--peak X] [--final Y] [--mu MU] [--tolerance N]

The top is pressed at t = 1 and held (P from a run of the press alone);
the tangential load rises to Q* = X mu P at t = 2 (two steps) and falls
back to Q = Y mu P at t = 3 (two steps): `Traction' = (mu P/(2R)) q(t), 0
with q the piecewise linear ramp, set here through --set.  Asserted, on the contact surface of the
last step (contact_1.vtu), positions along x:
  - at Q* (a history to t = 2): the stick half-width c (the outermost
    sticking node) against Cattaneo's c/a = sqrt(1 - Q*/(mu P)), a the
    contact half-width (outermost node under pressure), within N node
    spacings (default 1);
  - after unloading to Q (a history to t = 3): the nodes that slip again,
    backwards, lie outside c'/a = sqrt(1 - (Q* - Q)/(2 mu P)) and those
    inside stick: the stick half-width against c', within N spacings;
  - the tangential force is the load at both ends (1e-8).
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
    check, exit_status, read_results, run_steps)


def run(args, name, times, traction):
    return run_steps(args, name, times,
                     ["Body 1/Traction 1/Traction=" + traction,
                      "Body 1/Dirichlet 1/Displacement=0; -6e-3*min(t, 1)"])


def zone(out):
    """(a, c, spacing): contact and stick half-widths, node spacing."""
    points, fields = contact_vtu.read_contact_nodes(
        os.path.join(out, "contact_1.vtu"))
    x = points[:, 0]
    pressed = (fields["status"] == 1) | (fields["status"] == 2)
    stick = fields["status"] == 1
    a = numpy.abs(x[pressed]).max()
    c = numpy.abs(x[stick]).max() if stick.any() else 0.0
    spacing = numpy.median(numpy.diff(numpy.sort(x[pressed])))
    return a, c, spacing


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("app")
    parser.add_argument("input")
    parser.add_argument("workdir")
    parser.add_argument("--peak", type=float, default=0.6)
    parser.add_argument("--final", type=float, default=0.2)
    parser.add_argument("--mu", type=float, default=0.3)
    parser.add_argument("--tolerance", type=float, default=1.0)
    args = parser.parse_args()
    args.app, args.input = (os.path.abspath(p) for p in (args.app, args.input))
    shutil.rmtree(args.workdir, ignore_errors=True)
    os.makedirs(args.workdir)
    # the normal force of the press (the top's displacement held from
    # t = 1 on), then q(t) = Q(t) / (2R) in units of mu P / (2R)
    x, y, mu = args.peak, args.final, args.mu
    press = run(args, "press", "1", "0; 0")
    if press is None:
        return 1
    P = read_results(os.path.join(press, "results.txt"))[
        "pair_1.normal_force"][0]
    q = ("%.12g*(t <= 1 ? 0 : (t <= 2 ? %g*(t - 1) : %g - %g*(t - 2)))"
         % (mu * P / 2, x, x, x - y))
    traction = q + "; 0"
    cases = [("loaded", "1, 1.5, 2", math.sqrt(1 - x), x),
             ("unloaded", "1, 1.5, 2, 2.5, 3",
              math.sqrt(1 - (x - y) / 2), y)]
    for name, times, expected, share in cases:
        out = run(args, name, times, traction)
        if out is None:
            continue
        a, c, spacing = zone(out)
        check(abs(c - expected * a) <= args.tolerance * spacing,
              name + ": stick half-width c/a against %.4f" % expected,
              "c = %.5f, a = %.5f, c/a = %.4f, spacing %.5f (%.2f spacings)"
              % (c, a, c / a, spacing, abs(c - expected * a) / spacing))
        results = read_results(os.path.join(out, "results.txt"))
        force = results["pair_1.tangential_force"][0]
        load = share * mu * P
        check(abs(abs(force) - load) <= 1e-8 * load,
              name + ": tangential force = the load %g" % load, force)
    return exit_status()


if __name__ == "__main__":
    sys.exit(main())
