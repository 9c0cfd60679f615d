#!/usr/bin/env python3
"""Table 12 of the thesis (steel brick, Tresca friction) from the runs of
scripts/bench_brick.

Usage: brick_tables.py BENCH_DIR [--laws ...] [--levels ...] [--phis ...]
                       [--solvers ...] [--tolerances ...] [--thesis]

BENCH_DIR holds one folder per run, <law>_L<level>_phi<phi>_<solver>_tol<tol>,
with the run's out/statistics.json and run.json (postprocess/run_case.py).
Prints one Markdown table per friction law, mesh level and precision:
columns phi, and per solver the rows of table 12: active bound / quadratic
constraints in % of the contact nodes at the returned multipliers (the QP's
active set: lambda_N = 0, tangential multiplier on its ellipse or disc; see
active_sets()),
inner iterations, Hessian products, iterations by kind (CG, half-step,
projection = expansion steps including those after half-steps, BB steps,
fall-backs), the QP's wall time and the process' peak memory, and the
reason the solver stopped.  A run that did not converge shows its reason
and the relative criterion it reached, never "converged".

--thesis: table 12's figures beside ours in every cell, "ours [thesis]"
(its MPGP, MPGP-BB and SPG-QP; TFETI at 40 x 80 x 40, 1e-2 ||b||; its
inner iterations and products are summed over its SMALBE-M outer
iterations, ours are of the one undecomposed QP), percentages with one
decimal, and a row with the whole run's wall time, the process' peak
memory and the 1-minute load average when it started.
"""
import argparse
import json
import math
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import contact_vtu  # noqa: E402

NAMES = {"mpgp": "MPGP", "mpgp-bb": "MPGP-BB", "mwpgp": "MwPGP", "spg-qp": "SPG-QP",
         "pbbf": "PBBf", "apgd": "APGD", "mprgp": "MPRGP"}


# table 12 of the thesis (phi = 10, 30, 100, 500); SPG-QP: 50000 = not
# converged in 50000 iterations
THESIS_ACTIVE = {"10": (98, 97), "30": (98, 89), "100": (98, 59), "500": (99, 48)}
THESIS = {
    "mpgp": {"outer": (3, 3, 4, 4), "inner": (15087, 32877, 35384, 6148),
             "products": (26575, 34674, 35999, 7157), "cg": (11245, 11830, 8005, 5145),
             "half_step": (2818, 1793, 610, 1003), "expansion": (9690, 19254, 26769, 1)},
    "mpgp-bb": {"outer": (4, 3, 4, 4), "inner": (15389, 17417, 12747, 6148),
                "products": (18747, 20207, 14322, 7157), "cg": (11489, 13258, 9401, 5145),
                "half_step": (3353, 2786, 1570, 1003), "bb": (547, 1373, 1776, 1)},
    "spg-qp": {"outer": (3, 3, 4, 2), "inner": ("50000*",) * 4},
}
THESIS_PHIS = ["10", "30", "100", "500"]


def thesis_value(solver, key, phi):
    """Table 12's figure, or "" where it has none."""
    if phi not in THESIS_PHIS or key not in THESIS.get(solver, {}):
        return ""
    return str(THESIS[solver][key][THESIS_PHIS.index(phi)])


def load(case_dir):
    """(qp record, contact record, run record) of a run; None where missing.
    The contact record gets the active sets as `active_percent'."""
    run = stats = None
    path = os.path.join(case_dir, "run.json")
    if os.path.exists(path):
        run = json.load(open(path))
    path = os.path.join(case_dir, "out", "statistics.json")
    if os.path.exists(path):
        stats = json.load(open(path))
    if stats is None:
        return None, None, run
    contact = stats["contact"]
    qp = contact["qp_solves"][-1] if contact["qp_solves"] else None
    contact["active_percent"] = active_sets(case_dir)
    return qp, contact, run


def read_prm(path, name):
    m = re.search(r"^\s*set\s+" + re.escape(name) + r"\s*=\s*(.*)$", open(path).read(), re.M)
    return m.group(1).split("#")[0].strip() if m else None


def active_sets(case_dir):
    """(active bound %, active quadratic %) of the QP at the returned
    multipliers, from the contact surface out/contact_1.vtu: a bound
    lambda_N >= 0 is active where the pressure lambda_N / w_i is exactly 0
    (the solvers put multipliers exactly on their bounds), a friction
    ellipse / disc where the nodal utilization ||lambda_T||_E reaches
    1 - 1e-10: with psi_k = phi_k w_i and traction lambda_T / w_i the weight
    cancels, utilization = sqrt((t_1 / phi_1)^2 + (t_2 / phi_2)^2), t_1 along
    x and t_2 along y (the brick's tangents).  The percentages refer to all
    contact nodes, including the 2L + 1 nodes on the fixed edge y = z = 0,
    whose rows of B vanish (their multipliers stay 0)."""
    # the values the run used (brick.prm with the script's --set applied)
    prm = os.path.join(case_dir, "out", "used_parameters.prm")
    vtu = os.path.join(case_dir, "out", "contact_1.vtu")
    if not os.path.exists(vtu):
        return float("nan"), float("nan")
    if read_prm(prm, "Friction law") == "tresca orthotropic":
        phi = [float(v) for v in read_prm(prm, "Slip bounds").split(",")]
    else:
        phi = [float(read_prm(prm, "Slip bound"))] * 2
    _, fields = contact_vtu.read_contact_nodes(vtu)
    pressure = fields["pressure_Pa"]
    t = fields["tangential_traction_Pa"]
    n = len(pressure)
    bound = sum(1 for p in pressure if p == 0.0)
    quadratic = sum(1 for i in range(n)
                    if math.hypot(t[i, 0] / phi[0], t[i, 1] / phi[1]) >= 1 - 1e-10)
    return 100.0 * bound / n, 100.0 * quadratic / n


def outcome(qp, run):
    if run is not None and run.get("timeout"):
        return "stopped by the time limit (%.0f s)" % run["wall_time_s"]
    if qp is None:
        return "no statistics (exit %s)" % (run or {}).get("exit_code")
    if qp["converged"]:
        return "converged"
    crit = qp["final_criterion"]
    crit = "%.1e" % crit if isinstance(crit, (int, float)) else str(crit)
    return "**%s** (%s)" % (qp["reason"], crit)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("bench_dir")
    parser.add_argument("--laws", nargs="+", default=["orthotropic", "isotropic"])
    parser.add_argument("--levels", nargs="+", default=["10", "20"])
    parser.add_argument("--phis", nargs="+", default=["10", "30", "100", "500"])
    parser.add_argument("--solvers", nargs="+",
                        default=["mpgp", "mpgp-bb", "mwpgp", "spg-qp", "pbbf", "apgd"])
    parser.add_argument("--tolerances", nargs="+", default=["1e-2", "1e-4", "1e-6"])
    parser.add_argument("--thesis", action="store_true",
                        help="table 12's figures beside ours, and the run's time, memory and load")
    a = parser.parse_args()

    for law in a.laws:
        for level in a.levels:
            for tol in a.tolerances:
                cases = {(phi, s): load(os.path.join(
                    a.bench_dir, "%s_L%s_phi%s_%s_tol%s" % (law, level, phi, s, tol)))
                    for phi in a.phis for s in a.solvers}
                if all(c[2] is None for c in cases.values()):
                    continue
                level_i = int(level)
                first = next((c for c in cases.values() if c[1] is not None), None)
                size = ""
                if first is not None:
                    size = ", %d multipliers" % first[1]["n_multipliers"]
                print("\n#### %s Tresca, mesh %d x %d x %d%s, precision %s ||b||\n"
                      % (law, level_i, 2 * level_i, level_i, size, tol))
                print("| solver | row | " + " | ".join("phi = %s" % p for p in a.phis) + " |")
                print("|---|---|" + "---|" * len(a.phis))
                for s in a.solvers:
                    if a.thesis:
                        rows = thesis_rows(s)
                    else:
                        rows = [("active bound / quadratic %", lambda q, c, r, phi:
                                 "%.0f / %.0f" % c["active_percent"]),
                                ("inner iterations", lambda q, c, r, phi: "%d" % q["iterations"]),
                                ("Hessian products", lambda q, c, r, phi: "%d" % q["hessian_products"]),
                                ("CG / half-step / projection", lambda q, c, r, phi: "%d / %d / %d" % (
                                    q["iterations_by_kind"]["cg"], q["iterations_by_kind"]["half_step"],
                                    q["iterations_by_kind"]["expansion"])),
                                ("BB / fall-back", lambda q, c, r, phi: "%d / %d" % (
                                    q["iterations_by_kind"]["bb"], q["iterations_by_kind"]["fall_back"])),
                                ("QP time s / peak MB", lambda q, c, r, phi: "%.1f / %.0f" % (
                                    q["wall_time"], r["peak_memory_MB"] if r else float("nan"))),
                                ("outcome", None)]
                    for k, (label, cell) in enumerate(rows):
                        values = []
                        for phi in a.phis:
                            q, c, r = cases[(phi, s)]
                            if cell is None:
                                values.append(outcome(q, r) if r is not None else "not run")
                            elif q is None:
                                values.append("-")
                            else:
                                values.append(cell(q, c, r, phi))
                        print("| %s | %s | %s |" % (NAMES.get(s, s) if k == 0 else "", label,
                                                   " | ".join(values)))


def beside(ours, thesis):
    return "%s [%s]" % (ours, thesis) if thesis != "" else ours


def thesis_rows(s):
    """The rows of --thesis: ours [table 12's] in every cell."""
    def kind(q, key):
        return q["iterations_by_kind"][key]

    def active(q, c, r, phi):
        t = THESIS_ACTIVE.get(phi)
        return beside("%.1f / %.1f" % c["active_percent"],
                      "%d / %d" % t if t and s in THESIS else "")

    def by_kind(q, c, r, phi):
        ours = "%d / %d / %d" % (kind(q, "cg"), kind(q, "half_step"), kind(q, "expansion"))
        t = [thesis_value(s, key, phi) for key in ("cg", "half_step", "expansion")]
        return beside(ours, " / ".join(v or "-" for v in t) if any(t) else "")

    def bb(q, c, r, phi):
        return beside("%d / %d" % (kind(q, "bb"), kind(q, "fall_back")),
                      thesis_value(s, "bb", phi) + " / -" if thesis_value(s, "bb", phi) else "")

    def run_row(q, c, r, phi):
        if r is None:
            return "-"
        return "%.0f / %.1f / %.0f / %s" % (r["wall_time_s"], q["wall_time"], r["peak_memory_MB"],
                                             r["load_average"][0])
    return [("active bound / quadratic % [thesis]", active),
            ("inner iterations [thesis: summed over its outer]", lambda q, c, r, phi: beside(
                "%d" % q["iterations"], thesis_value(s, "inner", phi))),
            ("Hessian products [thesis]", lambda q, c, r, phi: beside(
                "%d" % q["hessian_products"], thesis_value(s, "products", phi))),
            ("CG / half-step / projection [thesis]", by_kind),
            ("BB / fall-back [thesis: PBB]", bb),
            ("wall s / QP s / peak MB / load", run_row),
            ("outcome", None)]


if __name__ == "__main__":
    main()
