#!/usr/bin/python3
"""ctest postprocess/speed_accuracy_quick: runs `scripts/bench_speed_accuracy
--quick' (the charts part, postprocess/speed_accuracy.py with its QUICK
configuration) in a fresh folder and checks what it produced:

  - every chart is a PNG of plausible size;
  - the run table has its columns and one row per planned run, and every
    quick run converged;
  - the work-precision data has one point per solver and mesh level / per
    solver and tolerance; the Hertz errors against the closed form are those
    of doc/hertz.md's coarse levels (below 0.1 in 2D, 0.2 in 3D) and fall
    with the level; the brick's error against the reference on a finer mesh
    lies in (1e-3, 1) and falls with the level; the algebraic error falls
    with the tolerance and is below 1e-5 at 1e-8;
  - the convergence histories have time stamps, iteration and product
    counts per entry, non-decreasing, starting above the tolerance and
    ending at or below it, the last iteration count that of the run;
  - the performance profiles cover every problem, the best solver of each
    problem has ratio 1, r_max is twice the largest ratio, and no run failed.

    speed_accuracy_quick.py SCRIPT BIN_DIR WORK_DIR
"""
import csv
import json
import math
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                "postprocess"))
import speed_accuracy  # noqa: E402

failures = []


def check(condition, what):
    print("%s: %s" % ("ok" if condition else "FAILED", what))
    if not condition:
        failures.append(what)


def main():
    script, bin_dir, work = sys.argv[1:4]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    out = os.path.join(work, "out")
    env = dict(os.environ, BIN_DIR=bin_dir, BENCH_DIR=os.path.join(work, "runs"),
               SPEED_ACCURACY_PARTS="charts", OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
    proc = subprocess.run([script, "--quick", "--out", out], env=env, stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, text=True)
    print(proc.stdout)
    check(proc.returncode == 0, "bench_speed_accuracy --quick exits with 0")
    if proc.returncode != 0:
        sys.exit(1)
    cfg = speed_accuracy.QUICK

    for name in (["work_precision_%s.png" % c for c in speed_accuracy.WORK_PRECISION_CASES] +
                 ["convergence_%s.png" % c for c in cfg["history_cases"]] +
                 ["profile_%s.png" % m for m in ("time", "iterations", "products")]):
        path = os.path.join(out, name)
        ok = os.path.exists(path) and os.path.getsize(path) > 20000 and \
            open(path, "rb").read(8) == b"\x89PNG\r\n\x1a\n"
        check(ok, "%s is a PNG of more than 20 kB" % name)

    rows = list(csv.DictReader(open(os.path.join(out, "speed_accuracy_runs.csv"))))
    check(list(rows[0].keys()) == speed_accuracy.RUN_COLUMNS if rows else False,
          "speed_accuracy_runs.csv has the columns %s" % ", ".join(speed_accuracy.RUN_COLUMNS))
    expected = 0
    for case in speed_accuracy.WORK_PRECISION_CASES:
        c = cfg[case]
        n_s = len(c["solvers"])
        # the tolerance sweep's point at the level tolerance is the level
        # sweep's run when the sweep level is one of the levels
        extra = [t for t in c["tolerances"]
                 if not (c["sweep_level"] in c["levels"] and t == c["level_tolerance"])]
        expected += (len(c["levels"]) + len(extra)) * n_s
        # the reference runs: on the sweep level, and (brick) on the finer
        # reference mesh
        expected += 2 if "reference_level" in c else 1
    for case, key in (("bridge", "levels"), ("cylinder", "moduli"), ("membrane", "sizes")):
        expected += len(cfg[case][key]) * len(cfg[case]["solvers"])
    check(len(rows) == expected, "%d runs in the table (expected %d)" % (len(rows), expected))
    not_converged = [(r["problem"], r["solver"], r["reason"]) for r in rows
                     if r["converged"] != "True"]
    check(not not_converged, "every quick run converged %s" % (not_converged or ""))
    by_problem = {}
    for r in rows:
        for k in ("iterations", "products", "qp_time_s"):
            check(r[k] != "" and float(r[k]) >= 0, "%s %s: %s recorded" % (r["problem"], r["solver"], k))
        by_problem[(r["problem"], r["solver"])] = r

    data = json.load(open(os.path.join(out, "speed_accuracy_data.json")))
    for case in speed_accuracy.WORK_PRECISION_CASES:
        c = cfg[case]
        wp = data["work_precision"][case]
        for s in c["solvers"]:
            levels = wp["levels"][s]
            tols = wp["tolerances"][s]
            check([p[0] for p in levels] == c["levels"],
                  "%s %s: one point per level %s" % (case, s, c["levels"]))
            check(sorted(p[0] for p in tols) == sorted(c["tolerances"]),
                  "%s %s: one point per tolerance %s" % (case, s, c["tolerances"]))
            errors = [p[3] for p in levels] + [p[3] for p in tols]
            check(all(e is not None and math.isfinite(e) and e > 0 for e in errors),
                  "%s %s: every error finite and positive" % (case, s))
            if case.startswith("hertz"):
                bound = 0.1 if case == "hertz_2d" else 0.2
                check(all(p[3] < bound for p in levels),
                      "%s %s: pressure L2 errors %s below %g" % (case, s, [p[3] for p in levels], bound))
            else:
                check(all(1e-3 < p[3] < 1 for p in levels),
                      "brick %s: traction errors %s against the finer reference in (1e-3, 1)"
                      % (s, ["%.2e" % p[3] for p in levels]))
            check(levels[-1][3] < levels[0][3],
                  "%s %s: the error falls from level %s to %s (%.3e -> %.3e)"
                  % (case, s, c["levels"][0], c["levels"][-1], levels[0][3], levels[-1][3]))
            alg = sorted((p[0], p[4]) for p in tols)
            check(all(a[1] is not None and a[1] > 0 for a in alg) and alg[0][1] < alg[-1][1]
                  and alg[0][1] < 1e-5,
                  "%s %s: algebraic error %s falls with the tolerance, < 1e-5 at %g"
                  % (case, s, ["%.1e" % a[1] for a in alg], alg[0][0]))

    for case, level in cfg["history_cases"].items():
        hist = data["convergence"][case]["solvers"]
        check(sorted(hist) == sorted(cfg[case]["solvers"]),
              "%s: one history per solver %s" % (case, cfg[case]["solvers"]))
        tol = cfg[case]["level_tolerance"] if case == "brick" else cfg[case]["tolerance"]
        for s, h in hist.items():
            n = len(h["criterion"])
            run = by_problem[("%s/%s/%g" % (case, level, tol), s)]
            ok = (n >= 2 and len(h["time_s"]) == n and len(h["iterations"]) == n and
                  len(h["products"]) == n and
                  all(b >= a for a, b in zip(h["time_s"], h["time_s"][1:])) and
                  all(b >= a for a, b in zip(h["iterations"], h["iterations"][1:])) and
                  all(b >= a for a, b in zip(h["products"], h["products"][1:])) and
                  h["criterion"][0] > tol >= h["criterion"][-1] and
                  h["iterations"][-1] == int(run["iterations"]) and
                  h["products"][-1] <= int(run["products"]) and
                  0 <= h["time_s"][-1] <= float(run["qp_time_s"]))
            check(ok, "%s %s: history of %d entries with time stamps and counts, from %.2e "
                  "to %.2e <= %g" % (case, s, n, h["criterion"][0], h["criterion"][-1], tol))

    problems = sorted({r["problem"] for r in rows if r["role"] != "reference"})
    for measure, _ in speed_accuracy.MEASURES:
        p = data["profiles"][measure]
        check(p["problems"] == problems and not p["unsolved"],
              "profile %s: all %d problems" % (measure, len(problems)))
        ratios = p["ratios"]
        check(all(r is not None for s in ratios for r in ratios[s]) and
              len(p["problems"]) == len(problems),
              "profile %s: every solver has a ratio on every problem" % measure)
        if failures:
            continue
        best = [min(ratios[s][k] for s in ratios) for k in range(len(problems))]
        largest = max(r for s in ratios for r in ratios[s])
        check(all(abs(b - 1) < 1e-12 for b in best) and abs(p["r_max"] - 2 * largest) < 1e-9 * largest
              and all(v == 0 for v in p["failures"].values()),
              "profile %s: best ratio 1 on every problem, r_max = 2 x largest ratio = %.3g, "
              "no failure" % (measure, p["r_max"]))
        # a ratio is the cost over the best cost of its problem
        for s in ratios:
            for k, prob in enumerate(problems):
                costs = [float(by_problem[(prob, t)][measure]) for t in ratios]
                floor = 1e-6 if measure == "qp_time_s" else 1.0
                mine = max(float(by_problem[(prob, s)][measure]), floor)
                expected_ratio = mine / max(min(costs), floor)
                if abs(ratios[s][k] - expected_ratio) > 1e-9 * expected_ratio:
                    check(False, "profile %s: ratio of %s on %s" % (measure, s, prob))

    if failures:
        print("%d check(s) failed" % len(failures))
        sys.exit(1)
    print("all checks passed")


if __name__ == "__main__":
    main()
