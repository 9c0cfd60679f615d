#!/usr/bin/python3
"""Dolan-More performance profiles and the result table of the FCLIB /
Siconos comparison (benchmarks/fclib_siconos.cc, scripts/bench_fclib).

    /usr/bin/python3 postprocess/fclib_profiles.py RESULTS.csv FIGURE_PREFIX TABLE.md

A run counts as solved when its final FCLIB error (the same measure for every
solver, computed from the returned r) is at most the tolerance it was given;
the solver's own verdict is listed beside it in the table.  Per problem the
ratio r_ps = t_ps / min_s t_ps over the solved runs; unsolved runs get r_max
(twice the largest finite ratio), so that their curve never reaches them
(postprocess/performance_profiles.py).  One figure per measure (time,
iterations) and tolerance.
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import performance_profiles  # noqa: E402


def load(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def profile(rows, tol, measure, prefix):
    runs = [r for r in rows if float(r["tolerance"]) == tol]
    problems = sorted({r["problem"] for r in runs})
    solvers = list(dict.fromkeys(r["solver"] for r in runs))
    costs = {p: {} for p in problems}
    for r in runs:
        solved = float(r["fclib_error"]) <= tol
        v = float(r[measure])
        if measure == "iterations" and v <= 0:
            v = 1.0
        if measure == "time_s":
            v = max(v, 1e-6)
        costs[r["problem"]][r["solver"]] = v if solved else None
    solved_problems, solvers, ratios, r_max, _ = \
        performance_profiles.performance_ratios(costs, solvers)
    if not solved_problems:
        return
    fig, ax = plt.subplots(figsize=(7, 4.5))
    colours = plt.get_cmap("tab20")
    # failures sit at r_max, beyond the drawn range: their curve stays
    # below 1
    performance_profiles.draw(
        ax, solvers, ratios, r_max,
        "time" if measure == "time_s" else "iteration count",
        colours=lambda k: colours(k % 20),
        style=lambda s: "-" if "/" in s else "--",
        title="Performance profile, %s, tolerance %g (%d problems)" % (
            "time" if measure == "time_s" else "iterations", tol, len(problems)))
    ax.set_ylabel("fraction of problems solved within tau")
    ax.legend(fontsize=7, ncol=2, loc="lower right")
    name = "%s_%s_%g.png" % (prefix, "time" if measure == "time_s" else "iterations", tol)
    fig.tight_layout()
    fig.savefig(name, dpi=110)
    plt.close(fig)
    print("wrote", name)


def table(rows, path):
    with open(path, "w") as out:
        out.write("| problem | contacts | tol | solver | says converged | error <= tol | iterations | W products | time [s] | final FCLIB error |\n")
        out.write("|---|---|---|---|---|---|---|---|---|---|\n")
        for r in rows:
            err = float(r["fclib_error"])
            out.write("| %s | %s | %g | %s | %s | %s | %s | %s | %.3g | %.2e |\n" % (
                r["problem"].replace(".hdf5", ""), r["contacts"], float(r["tolerance"]), r["solver"],
                "yes" if r["solver_converged"] == "1" else "no",
                "yes" if err <= float(r["tolerance"]) else "**no**",
                r["iterations"], r["products"] if r["products"] != "0" else "-",
                float(r["time_s"]), err))
    print("wrote", path)


def main():
    rows = load(sys.argv[1])
    prefix = sys.argv[2]
    for tol in sorted({float(r["tolerance"]) for r in rows}, reverse=True):
        for measure in ("time_s", "iterations"):
            profile(rows, tol, measure, prefix)
    table(rows, sys.argv[3])


if __name__ == "__main__":
    main()
