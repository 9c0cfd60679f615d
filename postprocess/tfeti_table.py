#!/usr/bin/env python3
"""Prints the table of scripts/bench_tfeti from its run folders.

Usage: tfeti_table.py BENCH_DIR

One row per run folder (L<level>_<method><subdomains>_tol<tol>_np<processes>
[_noprojector][_prec<preconditioner>]; without _np: 1 process;
_noprojector: SMALSE-M's penalty form without the coarse projector;
_prec: `QP solver/Preconditioner', lumped or dirichlet): processes, wall time
and peak memory (run.json, postprocess/run_case.py), subdomains, dofs of
the subdomains, multipliers, coarse problem order, SMALSE-M outer and
inner iterations, Hessian products, time of the factorizations and of the
QP (statistics.json), the largest jump between two copies of a dof
relative to the largest |u| (the gluing residual), and the outcome.
"""
import json
import os
import re
import sys


def main():
    bench_dir = sys.argv[1]
    rows = []
    for name in os.listdir(bench_dir):
        m = re.match(r"L(\d+)_(none|tfeti)(\d*)_tol([^_]*)(?:_np(\d+))?"
                     r"(_noprojector)?(?:_prec(\w+))?$", name)
        if not m:
            continue
        case = os.path.join(bench_dir, name)
        try:
            run = json.load(open(os.path.join(case, "run.json")))
        except OSError:
            continue
        stats_file = os.path.join(case, "out", "statistics.json")
        method = m.group(2)
        if method == "tfeti":
            method += " (penalty" if m.group(6) else " (projector"
            method += (", " + m.group(7) + ")") if m.group(7) else ")"
        row = {"level": int(m.group(1)), "method": method,
               "subdomains": int(m.group(3)) if m.group(3) else 0,
               "tol": m.group(4), "np": int(m.group(5) or 1),
               "wall": run["wall_time_s"],
               "peak": run["peak_memory_MB"], "load": run["load_average"][0],
               "outcome": "timeout" if run["timeout"] else
               {0: "converged", 2: "not converged"}.get(run["exit_code"], "error")}
        if os.path.exists(stats_file):
            contact = json.load(open(stats_file))["contact"]
            solves = contact["qp_solves"]
            row["outer"] = sum(q.get("iterations_by_kind", {}).get("outer", 0) for q in solves)
            row["inner"] = sum(q["iterations"] for q in solves)
            row["products"] = sum(q["hessian_products"] for q in solves)
            row["qp_time"] = contact["qp_wall_time_s"]
            row["setup"] = contact["stiffness_setup_time_s"]
            row["multipliers"] = contact["n_multipliers"]
            decomposition = contact.get("decomposition", {})
            row["n_sub"] = decomposition.get("n_subdomains", 1)
            row["dofs"] = decomposition.get("n_subdomain_dofs", "")
            row["coarse"] = decomposition.get("coarse_problem_order", 0)
            jump = decomposition.get("relative_interface_jump")
            row["jump"] = f"{jump:.1e}" if jump is not None else "-"
        rows.append(row)
    rows.sort(key=lambda r: (r["level"], float(r["tol"]), r["method"] != "none",
                             r["subdomains"], r["np"]))
    print("| mesh | tol | method | processes | subdomains | dofs | multipliers | coarse | "
          "outer / inner / products | factorization s | QP s | wall s | peak MB "
          "(largest process) | load | jump | outcome |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        L = r["level"]
        print(f"| {L}x{2*L}x{L} | {r['tol']} | {r['method']} | {r['np']} | "
              f"{r.get('n_sub', '-')} | "
              f"{r.get('dofs', '-')} | {r.get('multipliers', '-')} | {r.get('coarse', '-')} | "
              f"{r.get('outer', '-')} / {r.get('inner', '-')} / {r.get('products', '-')} | "
              f"{r.get('setup', 0):.1f} | {r.get('qp_time', 0):.1f} | {r['wall']:.1f} | "
              f"{r['peak']:.0f} | {r['load']} | {r.get('jump', '-')} | {r['outcome']} |")


if __name__ == "__main__":
    main()
