#!/usr/bin/env python3
"""Runs one input of dualcontact and asserts that every body's forces
balance: applied force + support reactions + contact force = 0.

Usage: check_balance.py DUALCONTACT INPUT.prm WORKDIR [--np N]
                        [--set KEY=VALUE ...] [--tolerance T]
                        [--symmetry BODY:BOUNDARY:AXIS ...]
                        [--mpirun MPIRUN]

The run (under `MPIRUN -np N' when N > 1) must exit 0.  Asserted, from its
results.txt and used_parameters.prm:
  - per body: body_N.force_imbalance <= T (default 1e-8), and the same
    number recomputed from the printed vectors, |applied_force + sum of
    reaction_force.boundary_* + contact_force| / (the largest of them),
    <= T: what the file says balances, not only what it claims;
  - Newton's third law over the pairs: a body's contact_force is the sum
    over its pairs of -pair_K.contact_force where it is the slave and
    +pair_K.contact_force where it is the master (to T relative to the
    largest pair force), and the bodies' contact forces add up to minus
    the forces of the pairs on obstacles;
  - --symmetry BODY:BOUNDARY:AXIS: the reaction of that support along
    AXIS (x, y, z) is zero to T relative to the body's largest force (a
    symmetry plane of a frictionless scene carries no load: nothing acts
    along it).
"""
import argparse
import math
import os
import re
import shutil
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, ".."))
import script_tools  # noqa: E402
from script_tools import (  # noqa: E402
    check, exit_status, mpi_launcher, run_app)


def read_results(path):
    """results.txt: a key's number, or its list of numbers (vectors)."""
    return {k: v[0] if len(v) == 1 else v
            for k, v in script_tools.read_results(path).items()}


def read_pairs(path):
    """Per contact pair number: (slave body, master body or None)."""
    pairs, stack = {}, []
    with open(path) as f:
        for raw in f:
            line = raw.split("#", 1)[0].strip()
            if line.startswith("subsection "):
                stack.append(line[len("subsection "):].strip())
            elif line == "end":
                stack.pop()
            elif line.startswith("set ") and len(stack) == 1:
                m = re.match(r"Contact pair (\d+)$", stack[0])
                if not m:
                    continue
                key, value = (s.strip() for s in line[4:].split("=", 1))
                entry = pairs.setdefault(int(m.group(1)), [None, None])
                if key == "Slave body":
                    entry[0] = int(value)
                elif key == "Master":
                    words = value.split()
                    entry[1] = int(words[1]) if words[0] == "body" else None
    return pairs


def norm(v):
    return math.sqrt(sum(x * x for x in v))


def add(a, b, sign=1.0):
    return [x + sign * y for x, y in zip(a, b)]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("app")
    parser.add_argument("input")
    parser.add_argument("workdir")
    parser.add_argument("--np", type=int, default=1)
    parser.add_argument("--mpirun", default="mpirun")
    parser.add_argument("--set", action="append", default=[])
    parser.add_argument("--tolerance", type=float, default=1e-8)
    parser.add_argument("--symmetry", action="append", default=[])
    args = parser.parse_args()
    args.app, args.input = (os.path.abspath(p) for p in (args.app, args.input))

    shutil.rmtree(args.workdir, ignore_errors=True)
    os.makedirs(args.workdir)
    launcher = mpi_launcher(args.mpirun, args.np)
    out = run_app(args.app, args.input, args.workdir, "output",
                  ["Output/Write VTU=false"] + args.set, launcher=launcher)
    if out is None:
        return 1
    results = read_results(os.path.join(out, "results.txt"))
    dim = int(results["dimension"])
    n_bodies = int(results["n_bodies"])
    pairs = read_pairs(os.path.join(out, "used_parameters.prm"))
    zero = [0.0] * dim
    as_vector = lambda v: v if isinstance(v, list) else [v]

    body_contact = {}
    for b in range(1, n_bodies + 1):
        prefix = "body_%d." % b
        applied = as_vector(results[prefix + "applied_force"])
        contact = as_vector(results.get(prefix + "contact_force", zero))
        body_contact[b] = contact
        total, scale = add(applied, contact), max(norm(applied), norm(contact))
        for key, value in results.items():
            if key.startswith(prefix + "reaction_force."):
                total = add(total, as_vector(value))
                scale = max(scale, norm(as_vector(value)))
        recomputed = norm(total) / scale if scale > 0 else 0.0
        reported = results[prefix + "force_imbalance"]
        check(reported <= args.tolerance,
              "body_%d.force_imbalance <= %g" % (b, args.tolerance), reported)
        check(recomputed <= args.tolerance,
              "body_%d: |applied + reactions + contact| / largest (from the "
              "printed vectors)" % b, "%.3e (forces up to %.6e)"
              % (recomputed, scale))

    # Newton's third law through the pairs
    expected = {b: list(zero) for b in range(1, n_bodies + 1)}
    on_obstacles, pair_scale = list(zero), 0.0
    for p, (slave, master) in sorted(pairs.items()):
        force = as_vector(results["pair_%d.contact_force" % p])
        pair_scale = max(pair_scale, norm(force))
        expected[slave] = add(expected[slave], force, -1.0)
        if master is None:
            on_obstacles = add(on_obstacles, force)
        else:
            expected[master] = add(expected[master], force)
    if pairs:
        worst = max(norm(add(body_contact[b], expected[b], -1.0))
                    for b in expected)
        check(worst <= args.tolerance * max(pair_scale, 1e-300),
              "each body's contact_force = the sum of its pairs' forces",
              "%.3e of %.6e" % (worst, pair_scale))
        total = list(on_obstacles)
        for b in body_contact:
            total = add(total, body_contact[b])
        check(norm(total) <= args.tolerance * max(pair_scale, 1e-300),
              "bodies' contact forces + obstacles' = 0",
              "%.3e of %.6e" % (norm(total), pair_scale))

    for spec in args.symmetry:
        body, boundary, axis = spec.split(":")
        prefix = "body_%s." % body
        reaction = as_vector(results[prefix + "reaction_force.boundary_"
                                     + boundary])
        scale = max(norm(as_vector(v)) for k, v in results.items()
                    if k.startswith(prefix) and k.endswith("force"))
        component = reaction["xyz".index(axis)]
        check(abs(component) <= args.tolerance * scale,
              "symmetry plane: body %s boundary %s reaction along %s"
              % (body, boundary, axis), "%.3e of %.6e" % (component, scale))
    return exit_status()


if __name__ == "__main__":
    sys.exit(main())
