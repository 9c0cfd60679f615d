#!/usr/bin/env python3
"""Prints the brick's TFETI table (issue 19: thesis section 3.2.3, table 12,
the thesis' formulation) from the run folders of
`SUBDOMAINS=16 scripts/bench_brick', with table 12's numbers beside.

Usage: brick_tfeti_table.py LABEL=BENCH_DIR [LABEL=BENCH_DIR ...]
           [--level L] [--phis ...] [--solvers ...] [--tolerance 1e-2]

One row per placement (LABEL), phi and solver: active bound / active
quadratic % (postprocess/brick_tables.py's active_sets: of all contact
nodes of out/contact_1.vtu), SMALSE-M outer iterations, inner iterations
and Hessian products (summed over the QP solves of statistics.json),
multipliers, wall time, peak memory and load average at the start
(run.json, postprocess/run_case.py), the outcome; then the thesis' row.
"""
import argparse
import json
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from brick_tables import active_sets, NAMES  # noqa: E402

# table 12 (40 x 80 x 40, 16 subdomains, 1e-2): bound %, quadratic %, and per
# solver (SMALBE-M outer, inner, Hessian products); SPG-QP: 50000* = the
# iteration limit (not converged), products not given
THESIS_SETS = {"10": (98, 97), "30": (98, 89), "100": (98, 59), "500": (99, 48)}
THESIS_ITS = {
    "mpgp": {"10": (3, 15087, 26575), "30": (3, 32877, 34674),
             "100": (4, 35384, 35999), "500": (4, 6148, 7157)},
    "mpgp-bb": {"10": (4, 15389, 18747), "30": (3, 17417, 20207),
                "100": (4, 12747, 14322), "500": (4, 6148, 7157)},
    "spg-qp": {"10": (3, "50000*", "-"), "30": (3, "50000*", "-"),
               "100": (4, "50000*", "-"), "500": (2, "50000*", "-")},
}


# table 12: CG / CG-half / projection (MPGP) or PBB (MPGP-BB)
THESIS_KINDS = {
    "mpgp": {"10": "11245 / 2818 / 9690 / -", "30": "11830 / 1793 / 19254 / -",
             "100": "8005 / 610 / 26769 / -", "500": "5145 / 1003 / 1 / -"},
    "mpgp-bb": {"10": "11489 / 3353 / - / 547", "30": "13258 / 2786 / - / 1373",
                "100": "9401 / 1570 / - / 1776", "500": "5145 / 1003 / - / 1"},
}


def row(case_dir):
    r = {}
    try:
        run = json.load(open(os.path.join(case_dir, "run.json")))
    except OSError:
        return None
    r["wall"] = "%.0f" % run["wall_time_s"]
    r["peak"] = "%.0f" % run["peak_memory_MB"]
    r["load"] = run["load_average"][0]
    r["outcome"] = ("time limit" if run["timeout"] else
                    {0: "converged", 2: "not converged"}.get(run["exit_code"], "error"))
    stats_file = os.path.join(case_dir, "out", "statistics.json")
    if run["timeout"]:
        # killed: the last progress line of the log (its inner solve's
        # iteration count, criterion and that solve's tolerance)
        # (the count restarts with every inner solve: solves and iterations
        # are lower bounds, the progress lines come every 5 s)
        last, solves, total = None, 0, 0
        for line in open(os.path.join(case_dir, "log.txt"), errors="replace"):
            m = re.search(r"iteration (\d+), criterion (\S+) \(tolerance (\S+)\)", line)
            if m:
                if last is None or int(m.group(1)) < int(last.group(1)):
                    solves += 1
                    total += int(last.group(1)) if last else 0
                last = m
        if last:
            total += int(last.group(1))
            r["outcome"] = ("time limit %.0f s: >= %d inner solves, >= %d iterations; the last "
                            "at criterion %s > %s" % (run["wall_time_s"], solves, total,
                                                      last.group(2), last.group(3)))
    if os.path.exists(stats_file):
        contact = json.load(open(stats_file))["contact"]
        solves = contact["qp_solves"]
        r["outer"] = sum(q.get("iterations_by_kind", {}).get("outer", 0) for q in solves)
        r["inner"] = sum(q["iterations"] for q in solves)
        r["products"] = sum(q["hessian_products"] for q in solves)
        kinds = {}
        for q in solves:
            for k, v in q.get("iterations_by_kind", {}).items():
                kinds[k] = kinds.get(k, 0) + v
        r["kinds"] = "%d / %d / %d / %d" % (kinds.get("cg", 0), kinds.get("half_step", 0),
                                          kinds.get("expansion", 0), kinds.get("bb", 0))
        r["multipliers"] = contact["n_multipliers"]
        r["subdomains"] = contact.get("decomposition", {}).get("n_subdomains", 1)
        b, q = active_sets(case_dir)
        r["sets"] = "%.1f / %.1f" % (b, q)
        if solves and not solves[-1]["converged"]:
            crit = solves[-1].get("final_criterion")
            r["outcome"] = "%s (%s)" % (solves[-1].get("reason", "not converged"),
                                        "%.1e" % crit if isinstance(crit, float) else crit)
    return r


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("dirs", nargs="+", help="LABEL=BENCH_DIR")
    parser.add_argument("--level", default="20")
    parser.add_argument("--phis", nargs="+", default=["10", "30", "100", "500"])
    parser.add_argument("--solvers", nargs="+", default=["mpgp", "mpgp-bb", "spg-qp"])
    parser.add_argument("--tolerance", default="1e-2")
    args = parser.parse_args()
    print("| placement | phi | solver | bound / quadratic % | thesis | outer / inner / products "
          "| thesis | CG / half-step / projection / BB | thesis | subdomains / multipliers "
          "| wall s | peak MB | load | outcome |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for spec in args.dirs:
        label, bench_dir = spec.split("=", 1)
        for phi in args.phis:
            for solver in args.solvers:
                case = os.path.join(bench_dir, "orthotropic_L%s_phi%s_%s_tol%s"
                                    % (args.level, phi, solver, args.tolerance))
                r = row(case) if os.path.isdir(case) else None
                ts = THESIS_SETS.get(phi)
                ti = THESIS_ITS.get(solver, {}).get(phi)
                thesis_sets = "%d / %d" % ts if ts else ""
                thesis_its = "%s / %s / %s" % ti if ti else ""
                thesis_kinds = THESIS_KINDS.get(solver, {}).get(phi, "")
                if r is None:
                    print(f"| {label} | {phi} | {NAMES.get(solver, solver)} | not run | "
                          f"{thesis_sets} | | {thesis_its} | | {thesis_kinds} | | | | | |")
                    continue
                print(f"| {label} | {phi} | {NAMES.get(solver, solver)} | {r.get('sets', '-')} | "
                      f"{thesis_sets} | {r.get('outer', '-')} / {r.get('inner', '-')} / "
                      f"{r.get('products', '-')} | {thesis_its} | {r.get('kinds', '-')} | {thesis_kinds} | "
                      f"{r.get('subdomains', '-')} / {r.get('multipliers', '-')} | {r['wall']} | "
                      f"{r['peak']} | {r['load']} | {r['outcome']} |")


if __name__ == "__main__":
    main()
