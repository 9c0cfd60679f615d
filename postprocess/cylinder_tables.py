#!/usr/bin/env python3
"""Table 11 of the thesis (floating cylinder in a rigid corner) from the runs
of scripts/bench_cylinder.

Usage: cylinder_tables.py BENCH_DIR [--formulations primal dual]
                          [--moduli ...] [--solvers ...]

primal: BENCH_DIR/primal.jsonl, one JSON object per run of
bench_contact_cylinder_primal (the thesis' bound-constrained QP with the
singular stiffness matrix).  dual: BENCH_DIR/dual_E<E>_<solver>/ with
out/statistics.json and run.json of a dualcontact run of inputs/cylinder.prm
(SMALSE-M around the solver).  Prints per formulation a Markdown table:
columns E [MPa], rows the spectrum (primal), the number of active
constraints (nodes in contact: primal bounds at the wall; dual normal
multipliers lambda_N > 0 from contact_N.vtu, i.e. bound constraints NOT
active), the relative force balance error |gravity + wall forces| /
|gravity| (dual) and per solver
"iterations / Hessian products" (dual: "outer / inner / products") or, for
a run that did not converge, its reason and the relative criterion reached.
"""
import argparse
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import contact_vtu  # noqa: E402

NAMES = {"mprgp": "MPRGP(S)", "mpgp": "MPGP", "mpgp-bb": "MPGP-BB", "mwpgp": "MwPGP",
         "spg-qp": "SPG-QP", "pbbf": "PBBf", "apgd": "APGD"}


def pascal(E):
    return float(E) * 1e6


def failed(q):
    crit = q["final_criterion"]
    crit = "%.1e" % crit if isinstance(crit, (int, float)) else str(crit)
    return "**%s** (%s)" % (q["reason"], crit)


def primal_table(bench_dir, moduli, solvers):
    path = os.path.join(bench_dir, "primal.jsonl")
    if not os.path.exists(path):
        return
    runs = {}
    for line in open(path):
        line = line.strip()
        if line.startswith("{"):
            r = json.loads(line)
            runs[(r["youngs_modulus_Pa"], r["statistics"]["solver"])] = r
    print("\n#### Primal bound-constrained QP (the thesis' formulation), "
          "precision 1e-4 ||b||\n")
    print("| | " + " | ".join("E = %s" % E for E in moduli) + " |")
    print("|---|" + "---|" * len(moduli))

    def any_run(E):
        return next((r for (e, s), r in runs.items() if e == pascal(E)), None)

    for label, f in [("n (dofs) / bounds", lambda r: "%d / %d" % (r["n_dofs"], r["n_bounds"])),
                     ("lambda_max(K)", lambda r: "%.4g" % r["lambda_max"]),
                     ("regular lambda_min(K)", lambda r: "%.4g" % r["lambda_min_regular"]),
                     ("regular kappa(K)", lambda r: "%.2f" % r["kappa_regular"]),
                     ("zero eigenvalues", lambda r: "%d" % r["n_zero_eigenvalues"]),
                     ("||b||", lambda r: "%.6g" % r["norm_b"])]:
        cells = []
        for E in moduli:
            r = any_run(E)
            cells.append(f(r) if r else "-")
        print("| %s | %s |" % (label, " | ".join(cells)))
    # active constraints: from the first converged run of each E
    cells = []
    for E in moduli:
        counts = sorted({r["n_active_bounds"] for (e, s), r in runs.items()
                         if e == pascal(E) and r["statistics"]["converged"]})
        cells.append("/".join(str(c) for c in counts) if counts else "-")
    print("| active (converged runs) | %s |" % " | ".join(cells))
    for s in solvers:
        cells = []
        for E in moduli:
            r = runs.get((pascal(E), s))
            if r is None:
                cells.append("not run")
                continue
            q = r["statistics"]
            if q["converged"]:
                cells.append("%d / %d" % (q["iterations"], q["hessian_products"]))
            else:
                cells.append("%s after %d / %d" % (failed(q), q["iterations"],
                                                   q["hessian_products"]))
        print("| %s | %s |" % (NAMES.get(s, s), " | ".join(cells)))


def in_contact(out_dir):
    """Nodes with a positive normal multiplier (pressure > 0) on both walls,
    from contact_1.vtu and contact_2.vtu: in the dual these are the bound
    constraints lambda_N >= 0 that are NOT active."""
    count = 0
    for k in (1, 2):
        _, fields = contact_vtu.read_contact_nodes(
            os.path.join(out_dir, "contact_%d.vtu" % k))
        count += int((fields["pressure_Pa"] > 0).sum())
    return count


def read_results(path):
    values = {}
    for line in open(path):
        if "=" in line and not line.startswith("#"):
            key, value = line.split("=", 1)
            try:
                values[key.strip()] = [float(v) for v in value.split(",")]
            except ValueError:
                pass
    return values


def error_text(log):
    for line in open(log):
        if line.startswith("Error:"):
            return line[len("Error:"):].strip().split(":")[0]
    return "see " + log


def dual_table(bench_dir, moduli, solvers):
    cases = {}
    for E in moduli:
        for s in solvers:
            d = os.path.join(bench_dir, "dual_E%s_%s" % (E, s))
            stats = run = None
            if os.path.exists(os.path.join(d, "run.json")):
                run = json.load(open(os.path.join(d, "run.json")))
            if os.path.exists(os.path.join(d, "out", "statistics.json")):
                stats = json.load(open(os.path.join(d, "out", "statistics.json")))
            cases[(E, s)] = (stats, run)
    if all(run is None for stats, run in cases.values()):
        return
    print("\n#### Dual QP with SMALSE-M (the application), precision 1e-4 ||b||\n")
    print("| | " + " | ".join("E = %s" % E for E in moduli) + " |")
    print("|---|" + "---|" * len(moduli))
    cells = []
    for E in moduli:
        st = next((c[0] for (e, s), c in cases.items() if e == E and c[0]), None)
        cells.append("%d / %d" % (st["contact"]["n_multipliers"],
                                  st["contact"]["n_rigid_body_modes"]) if st else "-")
    print("| multipliers / rigid-body modes | %s |" % " | ".join(cells))
    cells = []
    for E in moduli:
        counts = set()
        for (e, s), (st, run) in cases.items():
            if e == E and st and st["contact"]["converged"]:
                counts.add(in_contact(os.path.join(bench_dir, "dual_E%s_%s" % (e, s), "out")))
        cells.append("/".join(str(c) for c in sorted(counts)) if counts else "-")
    print("| nodes in contact (converged runs) | %s |" % " | ".join(cells))
    cells = []
    for E in moduli:
        errors = []
        for (e, s), (st, run) in cases.items():
            if e == E and st and st["contact"]["converged"]:
                r = read_results(os.path.join(bench_dir, "dual_E%s_%s" % (e, s), "out",
                                              "results.txt"))
                applied = r["body_1.applied_force"]
                total = [applied[0] + r["pair_1.normal_force"][0],
                         applied[1] + r["pair_2.normal_force"][0]]
                errors.append(math.hypot(*total) / math.hypot(*applied))
        cells.append("%.0e .. %.0e" % (min(errors), max(errors)) if errors else "-")
    print("| force balance error (converged runs) | %s |" % " | ".join(cells))
    for s in solvers:
        cells = []
        for E in moduli:
            st, run = cases[(E, s)]
            if run is None:
                cells.append("not run")
            elif st is None:
                cells.append("**error**, exit %s: %s" % (run["exit_code"], error_text(
                    os.path.join(bench_dir, "dual_E%s_%s" % (E, s), "log.txt"))))
            else:
                q = st["contact"]["qp_solves"][-1]
                counts = "%d / %d / %d" % (q["iterations_by_kind"]["outer"], q["iterations"],
                                           q["hessian_products"])
                cells.append(counts if q["converged"] else "%s after %s" % (failed(q), counts))
        print("| SMALSE-M + %s | %s |" % (NAMES.get(s, s), " | ".join(cells)))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("bench_dir")
    parser.add_argument("--formulations", nargs="+", default=["primal", "dual"])
    parser.add_argument("--moduli", nargs="+", default=["1", "10", "100", "1e4", "1e6", "1e8"])
    parser.add_argument("--solvers", nargs="+",
                        default=["mprgp", "mpgp", "mpgp-bb", "mwpgp", "spg-qp", "pbbf", "apgd"])
    a = parser.parse_args()
    if "primal" in a.formulations:
        primal_table(a.bench_dir, a.moduli, a.solvers)
    if "dual" in a.formulations:
        dual_table(a.bench_dir, a.moduli, a.solvers)


if __name__ == "__main__":
    main()
