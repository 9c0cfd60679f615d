#!/usr/bin/python3
"""The stability matrix of issue 6 as a markdown table and a heatmap.

Usage: /usr/bin/python3 stability_matrix.py STABILITY.json [--md FILE.md]
           [--png FILE.png] [--command "..."]

Reads the outcomes written by postprocess/stability_sweep.py (run by
scripts/bench_stability) and writes
  FILE.md  (default doc/stability.md): per scenario a table, rows = the
           scenario's parameter, columns = solvers; a cell is
           "123" (converged: QP iterations, summed over the Coulomb
           iterates), or the failure reason with the criterion reached
           (||g^P|| / ||b||), "n/a" (the solver does not take the
           constraint set: MPRGP on discs and ellipses), "error" (the run
           stopped with exit code 1, message in the notes); `auto` cells
           name the solver that won and the fall-backs taken;
  FILE.png (default doc/figures/stability_matrix.png): the heatmap, one
           row per scenario value, one column per solver: converged cells
           shaded by log10(iterations), failures red, n/a / error grey.
Run with /usr/bin/python3 (Debian's matplotlib and numpy).
"""
import argparse
import json
import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

SHORT = {"max_iterations": "max-it", "stagnation": "stagn.", "breakdown": "breakdown",
         "non_finite": "non-finite", "unbounded": "unbounded"}


def failure_kind(case):
    """Short reason of a failed run: the QP's, or the Coulomb loop's."""
    reason = case.get("reason", "")
    if "diverged" in reason:
        return "Coulomb diverged"
    if reason.startswith("Coulomb fixed point: maximum"):
        return "Coulomb max-it"
    if reason.startswith("Coulomb fixed point"):
        return "Coulomb " + reason.split(":")[-1].strip()
    return SHORT.get(case.get("qp_reason", ""), case.get("qp_reason", "failed"))


def cell_text(case, markdown=True):
    status = case["status"]
    if status == "converged":
        text = "%d" % case["iterations"]
        if case.get("n_qp_solves", 1) > 1:
            text += " (%d QPs)" % case["n_qp_solves"]
        if case.get("attempts") is not None and case.get("fall_backs", 0) > 0:
            chosen = sorted(set(f["chosen_solver"] for f in case.get("fall_back_solves", [])))
            text += (" via %s" if markdown else "\nvia %s") % "/".join(chosen)
        return text
    if status == "failed":
        kind = failure_kind(case)
        if kind.startswith("Coulomb") and case.get("coulomb_changes"):
            # the fixed point failed: the last relative change of psi
            change = case["coulomb_changes"][-1]
            text = "%s, change %.1e" % (kind, change) if markdown else \
                "%s\n%.0e" % (kind, change)
            return ("**%s**" % text) if markdown else text
        text = "%s %.1e" % (kind, case["final_criterion"]) if markdown else \
            "%s\n%.0e" % (kind, case["final_criterion"])
        return ("**%s**" % text) if markdown else text
    if status == "timeout":
        return "**timeout**" if markdown else "timeout"
    if status == "n/a":
        return "n/a"
    return "**error**" if markdown else "error"


def auto_note(case):
    def chain(attempts):
        return ", then ".join("%s %s (%d it, %.1e)" % (a["solver"], a["reason"], a["iterations"],
                                                        a["final_criterion"]) for a in attempts)
    if not case.get("attempts"):
        return None
    if case.get("n_qp_solves", 1) == 1:
        return chain(case["attempts"])
    # a Coulomb fixed point: the QPs that fell back, and the last QP
    parts = ["QP %d: %s" % (f["qp"], chain(f["attempts"]))
             for f in case.get("fall_back_solves", [])]
    if not case.get("fall_back_solves") or case["fall_back_solves"][-1]["qp"] != case["n_qp_solves"]:
        parts.append("last QP (%d): %s" % (case["n_qp_solves"], chain(case["attempts"])))
    return "; ".join(parts)


def spread(row):
    """Largest difference of the contact force between two converged runs
    of a row, relative to the largest force: ~tolerance when the solution
    is unique, large when the solvers found different solutions."""
    forces = [c["contact_force"] for c in row["cases"].values()
              if c["status"] == "converged" and c.get("contact_force")]
    if len(forces) < 2:
        return "-"
    size = max(math.sqrt(sum(v * v for v in f)) for f in forces)
    if size == 0:
        return "0"
    worst = max(math.sqrt(sum((a - b) ** 2 for a, b in zip(f, g)))
                for f in forces for g in forces)
    return "%.0e" % (worst / size)


def write_markdown(data, path, command, figure, notes_file=None):
    solvers = data["solvers"]
    out = []
    out.append("# The stability matrix\n")
    out.append("Scenarios x QP solvers (issue 6): the outcome of every run of "
               "`dualcontact` as its `statistics.json` reports it.  A number is "
               "a converged run's QP iterations (summed over the QPs of a "
               "Coulomb fixed point, their count in brackets); a bold entry is "
               "a failure with its reason and the relative criterion "
               "||g^P|| / ||b|| it reached (for SMALSE-M the larger of the "
               "Lagrangian's projected gradient and the scaled equality "
               "residual); *n/a*: the solver does not take the constraint set "
               "(MPRGP takes bounds and boxes only); *error*: the run stopped "
               "with exit code 1 (message below).  `auto` is the fall-back "
               "chain of `lib/qp/solver_chain.h`: *via X* names the solver "
               "that converged after a fall-back.  *spread*: the largest "
               "difference of the total contact force (normal and tangential, "
               "summed over the pairs) between two converged runs of the row, "
               "relative to the force: near the tolerance when the solvers "
               "agree, large when they found different solutions "
               "(non-uniqueness, or a loose criterion).\n")
    out.append("Settings for every run: ||g^P|| <= %g ||b|| (projected gradient), at most %d "
               "iterations per QP, stagnation window 1000, SMALSE-M outer limit as in the "
               "input (cylinder and Coulomb block 1000, two bodies 100), Coulomb fixed "
               "point to a relative change of %g (its failures show the last change), "
               "time limit %g s per run.\n"
               % (data["tolerance"], data["max_iterations"], 100 * data["tolerance"],
                  data["time_limit_s"]))
    out.append("Command: `%s`  \nRun %s, %s cores, load average %s at the start and %s at "
               "the end (the machine is shared), %.0f s in all (runs already on disk are not "
               "repeated).  No times are compared here, only outcomes and counts.\n"
               % (command, data["started"], data["cores"], " ".join(data["load_average_start"]),
                  " ".join(data["load_average_end"]), data["wall_time_s"]))
    if figure:
        out.append("![The stability matrix](%s)\n" % figure)
    if notes_file and os.path.exists(notes_file):
        # the hand-written reading of the matrix (not generated)
        out.append("## Findings\n")
        out.append("*From `%s` (written by hand for the committed run; "
                   "check it against the tables when they change).*\n"
                   % os.path.relpath(notes_file, os.path.dirname(os.path.abspath(path))))
        out.append(open(notes_file).read().strip() + "\n")
    notes = []
    for scenario in data["scenarios"]:
        out.append("## %s\n" % scenario["title"])
        out.append("Input `%s`, parameter %s [%s].\n" % (scenario["input"], scenario["parameter"],
                                                         scenario["unit"]))
        out.append("| %s | %s | spread |" % (scenario["parameter"], " | ".join(solvers)))
        out.append("|---|" + "---|" * len(solvers) + "---|")
        for row in scenario["rows"]:
            cells = []
            for s in solvers:
                case = row["cases"].get(s)
                cells.append(cell_text(case) if case else "-")
                if case and case["status"] == "error":
                    notes.append("%s %s = %g, %s: %s" % (scenario["key"], scenario["parameter"],
                                                         row["value"], s, case.get("message", "")))
                if case and s == "auto" and auto_note(case) and \
                        (case.get("fall_backs", 0) > 0 or case["status"] != "converged"):
                    notes.append("%s %s = %g, auto: %s" % (scenario["key"], scenario["parameter"],
                                                           row["value"], auto_note(case)))
            out.append("| %g | %s | %s |" % (row["value"], " | ".join(cells), spread(row)))
        out.append("")
    if notes:
        out.append("## Notes on single runs\n")
        for n in notes:
            out.append("- " + n)
        out.append("")
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with open(path, "w") as f:
        f.write("\n".join(out))


def draw(data, path):
    solvers = data["solvers"]
    labels, values, texts = [], [], []
    for scenario in data["scenarios"]:
        for row in scenario["rows"]:
            labels.append("%s  %s = %g" % (scenario["key"], scenario["parameter"], row["value"]))
            v_row, t_row = [], []
            for s in solvers:
                case = row["cases"].get(s, {"status": "missing"})
                status = case["status"]
                if status == "converged":
                    v_row.append(math.log10(max(case["iterations"], 1)))
                elif status in ("failed", "timeout"):
                    v_row.append(-1.0)
                else:
                    v_row.append(-2.0)
                t_row.append(cell_text(case, markdown=False) if status != "missing" else "")
            values.append(v_row)
            texts.append(t_row)
    values = np.array(values)
    n_rows, n_cols = values.shape
    fig, ax = plt.subplots(figsize=(1.25 * n_cols + 3.5, 0.36 * n_rows + 1.6))
    top = max(values.max(), 1.0)
    converged = np.ma.masked_where(values < 0, values)
    ax.imshow(np.where(values == -2.0, 1.0, np.nan), cmap="Greys", vmin=0, vmax=4,
              aspect="auto")
    ax.imshow(np.where(values == -1.0, 1.0, np.nan), cmap="Reds", vmin=0, vmax=1.6,
              aspect="auto")
    image = ax.imshow(converged, cmap="YlGn_r", vmin=0, vmax=top + 0.5, aspect="auto")
    for i in range(n_rows):
        for j in range(n_cols):
            ax.text(j, i, texts[i][j], ha="center", va="center", fontsize=5.5)
    ax.set_xticks(range(n_cols))
    ax.set_xticklabels(solvers)
    ax.xaxis.tick_top()
    ax.set_yticks(range(n_rows))
    ax.set_yticklabels(labels, fontsize=7)
    # separators between scenarios
    row = 0
    for scenario in data["scenarios"][:-1]:
        row += len(scenario["rows"])
        ax.axhline(row - 0.5, color="black", linewidth=1.0)
    bar = fig.colorbar(image, ax=ax, fraction=0.03, pad=0.02)
    bar.set_label("log10(QP iterations), converged runs")
    ax.set_title("green: converged (QP iterations); red: failed (reason,\n"
                 "||g^P||/||b|| reached); grey: n/a or error.  Tolerance %g ||b||,\n"
                 "at most %d iterations per QP"
                 % (data["tolerance"], data["max_iterations"]), fontsize=8)
    fig.tight_layout()
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    fig.savefig(path, dpi=130)


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("stability_json")
    parser.add_argument("--md", default=os.path.join(root, "doc", "stability.md"))
    parser.add_argument("--png", default=os.path.join(root, "doc", "figures",
                                                      "stability_matrix.png"))
    parser.add_argument("--command", default="scripts/bench_stability")
    parser.add_argument("--notes", default=None,
                        help="markdown file included as the Findings section")
    args = parser.parse_args()
    data = json.load(open(args.stability_json))
    draw(data, args.png)
    figure = os.path.relpath(args.png, os.path.dirname(os.path.abspath(args.md)))
    write_markdown(data, args.md, args.command, figure, args.notes)
    print("stability_matrix: wrote %s and %s" % (args.md, args.png))


if __name__ == "__main__":
    main()
