#!/usr/bin/env python3
"""Smoke test of a benchmark input of dualcontact (doc/benchmarks/).

Usage: check_benchmark.py DUALCONTACT brick|cylinder INPUT.prm WORKDIR
           [--balance TOL] [--feasibility REL] [--fall-back]

Runs INPUT.prm in WORKDIR and asserts, from results.txt, statistics.json
and contact_*.vtu:
  both:     exit code 0, contact.converged, the QP record converged with
            KKT stationarity <= 10 * tolerance * ||b||, complementarity
            (a gradient times a multiplier) <= 10 * tolerance * ||b|| * the
            total contact force, feasibility <= 1e-10 ||b||; the multipliers match the
            contact nodes;
  brick:    force balance: applied force + reaction at the fixed face
            (boundary id 2) + contact force on the brick = 0 to 1e-8
            relative; the tangential contact force lies within the slip
            bounds summed over the contact area (|F_x| <= phi_1 A,
            |F_y| <= phi_2 A); every node's tangential traction lies in its
            ellipse (or disc) up to 1e-8; and, the load being far above
            what friction carries, at least 90 % of the friction constraints
            are active (utilization >= 1 - 1e-10; the thesis: 97 % at
            phi = 10);
  cylinder: force balance of the floating disc: applied force (gravity) +
            the two walls' normal forces = 0 to 1e-8 relative; the scene is
            symmetric about the diagonal, so both walls carry the same
            force to 1e-6; each wall carries weight / sqrt(2); both walls
            have nodes in contact, as many as the status counts say.
Options (defaults for the benchmark inputs at tolerance 1e-10):
  --balance TOL      cylinder: force balance and weight / sqrt(2) per wall to
                     TOL relative (1e-8), symmetry to max(TOL, 1e-6);
  --feasibility REL  KKT feasibility <= REL ||b|| (1e-10; with SMALSE-M it
                     holds the equality residual ||G lambda - e||);
  --fall-back        the QP was solved by the solver `auto` after a fall-back:
                     at least two attempts, the first not converged, the
                     returned one converged.
Prints the measured values.
"""
import json
import math
import os
import re
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                "..", "..", "postprocess"))
import contact_vtu  # noqa: E402

failures = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what)
    if not ok:
        failures.append(what)


def read_results(path):
    values = {}
    for line in open(path):
        if "=" in line:
            key, value = line.split("=", 1)
            parts = [p.strip() for p in value.split(",")]
            try:
                values[key.strip()] = [float(p) for p in parts]
            except ValueError:
                values[key.strip()] = value.strip()
    return values


def read_prm(path, name):
    m = re.search(r"^\s*set\s+" + re.escape(name) + r"\s*=\s*(.*)$", open(path).read(), re.M)
    return m.group(1).split("#")[0].strip() if m else None


def read_vtu(path):
    """The point fields of the contact nodes of a contact-surface file."""
    return contact_vtu.read_contact_nodes(path)[1]


def norm(v):
    return math.sqrt(sum(x * x for x in v))


def main():
    app, kind, prm, workdir = sys.argv[1:5]
    options = sys.argv[5:]
    balance = float(options[options.index("--balance") + 1]) if "--balance" in options else 1e-8
    feasibility = float(options[options.index("--feasibility") + 1]) \
        if "--feasibility" in options else 1e-10
    shutil.rmtree(workdir, ignore_errors=True)
    os.makedirs(workdir)
    run = subprocess.run([app, os.path.abspath(prm)], cwd=workdir, capture_output=True,
                         text=True)
    print(run.stdout[-3000:])
    print(run.stderr[-3000:])
    check(run.returncode == 0, "exit code %d" % run.returncode)
    if run.returncode != 0:
        sys.exit(1)
    folder = os.path.join(workdir, read_prm(prm, "Output folder"))
    r = read_results(os.path.join(folder, "results.txt"))
    stats = json.load(open(os.path.join(folder, "statistics.json")))
    contact = stats["contact"]
    q = contact["qp_solves"][-1]
    check(contact["converged"] and q["converged"],
          "converged: %s, %s in %d iterations" % (contact["reason"], q["reason"],
                                                 q["iterations"]))
    scale = q["tolerance"] * q["norm_b"]
    kkt = q["kkt"]
    # complementarity sum_j mu_j dist_j is a gradient times a multiplier:
    # relative to the multipliers' size, the total contact force [N]
    force = sum(p["normal_force"] + norm(p["tangential_force"]) for p in contact["pairs"])
    check(kkt["stationarity"] <= 10 * scale
          and kkt["complementarity"] <= 10 * scale * max(1.0, force)
          and kkt["feasibility"] <= feasibility * q["norm_b"],
          "KKT stationarity %.2e, complementarity %.2e, feasibility %.2e (tolerance * ||b|| = "
          "%.2e, total contact force %.4g N)"
          % (kkt["stationarity"], kkt["complementarity"], kkt["feasibility"], scale, force))
    if "--fall-back" in options:
        attempts = q.get("attempts", [])
        check(q["solver"] == "auto" and len(attempts) >= 2
              and attempts[0]["reason"] != "converged"
              and attempts[q["chosen_attempt"]]["converged"]
              and q["chosen_attempt"] == len(attempts) - 1,
              "auto fell back: %s" % ", then ".join(
                  "%s %s" % (a["solver"], a["reason"]) for a in attempts))
    n_nodes = sum(p["n_nodes"] for p in contact["pairs"])
    check(contact["n_multipliers"] == (3 if kind == "brick" else 1) * n_nodes,
          "%d multipliers for %d contact nodes" % (contact["n_multipliers"], n_nodes))
    applied = r["body_1.applied_force"]

    if kind == "brick":
        reaction = r["body_1.reaction_force.boundary_2"]
        normal = r["pair_1.normal_force"][0]
        tangential = r["pair_1.tangential_force"]
        area = r["pair_1.area"][0]
        # the contact's force on the brick: -(lambda_N n + lambda_T t), n = (0, 0, -1)
        contact_force = [-tangential[0], -tangential[1], normal - tangential[2]]
        total = [applied[i] + reaction[i] + contact_force[i] for i in range(3)]
        check(norm(total) <= 1e-8 * norm(applied),
              "force balance: applied %s + reaction %s + contact %s = %s"
              % (applied, reaction, contact_force, total))
        law = read_prm(prm, "Friction law")
        if law == "tresca orthotropic":
            phi = [float(v) for v in read_prm(prm, "Slip bounds").split(",")]
        else:
            phi = [float(read_prm(prm, "Slip bound"))] * 2
        check(abs(tangential[0]) <= phi[0] * area * (1 + 1e-8)
              and abs(tangential[1]) <= phi[1] * area * (1 + 1e-8),
              "tangential contact force %s within the slip bounds (%g, %g) N"
              % (tangential, phi[0] * area, phi[1] * area))
        surface = read_vtu(os.path.join(folder, "contact_1.vtu"))
        worst = max(math.hypot(t[0] / phi[0], t[1] / phi[1])
                    for t in surface["tangential_traction_Pa"])
        check(worst <= 1 + 1e-8, "largest nodal friction utilization %.12f <= 1" % worst)
        active = sum(1 for t in surface["tangential_traction_Pa"]
                     if math.hypot(t[0] / phi[0], t[1] / phi[1]) >= 1 - 1e-10)
        check(active >= 0.9 * n_nodes,
              "active friction constraints %d of %d nodes (%.1f %%)"
              % (active, n_nodes, 100.0 * active / n_nodes))
    elif kind == "cylinder":
        f1 = r["pair_1.normal_force"][0]
        f2 = r["pair_2.normal_force"][0]
        # wall 1 (x = 0) pushes along +x, wall 2 (y = 0) along +y
        total = [applied[0] + f1, applied[1] + f2]
        check(norm(total) <= balance * norm(applied),
              "force balance: gravity %s + walls (%.10g, %.10g) = %s (%.1e relative)"
              % (applied, f1, f2, total, norm(total) / norm(applied)))
        check(abs(f1 - f2) <= max(balance, 1e-6) * abs(f1),
              "symmetry: wall forces %.10g and %.10g" % (f1, f2))
        check(abs(f1 - norm(applied) / math.sqrt(2)) <= balance * norm(applied),
              "each wall carries weight / sqrt(2) = %.10g" % (norm(applied) / math.sqrt(2)))
        in_contact = [sum(1 for p in read_vtu(os.path.join(folder, "contact_%d.vtu" % k))
                          ["pressure_Pa"] if p > 0) for k in (1, 2)]
        separated = sum(p["n_separated"] for p in contact["pairs"])
        check(min(in_contact) >= 1 and sum(in_contact) == n_nodes - separated,
              "nodes in contact: %s (pressure > 0), %d (status)"
              % (in_contact, n_nodes - separated))
    else:
        sys.exit("unknown benchmark kind " + kind)
    if failures:
        print("%d check(s) failed" % len(failures))
        sys.exit(1)
    print("all checks passed")


if __name__ == "__main__":
    main()
