#!/usr/bin/env python3
"""Runs the stability matrix of issue 6: scenarios x QP solvers.

Usage: stability_sweep.py DUALCONTACT ROOT BENCH_DIR [--quick]
           [--tolerance T] [--max-iterations N] [--time-limit S]
           [--solvers "a b c"] [--scenarios "cylinder brick ..."]

Each case is one run of DUALCONTACT (through postprocess/run_case.py) on an
unedited input of ROOT/inputs/ with `--set' arguments for the scenario's
parameter and the QP settings, in BENCH_DIR/<scenario>/<value>_<solver>/.
A case whose folder holds the same arguments (case.args) and a run.json is
not run again (delete the folder to redo it).  The outcome of each run is read from its
statistics.json (converged, reason, iterations, Hessian products, final
criterion, KKT residuals, the attempts of the solver `auto`) and log.txt
(the error of a run that stopped with exit code 1), and all outcomes are
written to BENCH_DIR/stability.json for postprocess/stability_matrix.py.

Every scenario uses the same QP settings: relative tolerance T (default
1e-6) of the projected gradient, at most N (default 10000, table 14 of the
thesis) iterations per QP, the application's stagnation window (1000), VTU
output off; the SMALSE-M outer limit is the input's (cylinder and Coulomb
block 1000, two bodies the default 100), the Coulomb tolerance 100 T.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import time

SOLVERS = "mprgp mpgp mpgp-bb mwpgp spg-qp pbbf apgd auto"
TOLERANCE = [1e-6]  # set from --tolerance


def fmt(value):
    return "%g" % value


# scenario: (title, input, parameter label, unit, values, edits(value) ->
# [(subsection path, name, value)])
def scenarios(quick):
    def cylinder(E):
        return [(("Body 1", "Material 1"), "Young's modulus", "%g" % (float(E) * 1e6))]

    def brick(phi):
        return [(("Body 1", "Mesh"), "Subdivisions", "4, 8, 4"),
                (("Contact pair 1",), "Slip bounds", "%g, %g" % (phi, phi / 2.0))]

    def orthotropic(ratio):
        return [(("Body 1", "Mesh"), "Subdivisions", "4, 8, 4"),
                (("Contact pair 1",), "Slip bounds", "%g, %g" % (10.0, 10.0 / ratio))]

    def coulomb(mu):
        # the fixed point's tolerance 100 times the QP's (the input's
        # ratio, 1e-8 / 1e-10): its change cannot fall below the QPs' error
        return [(("Output",), "Write Coulomb iterates", "false"),
                (("Coulomb",), "Tolerance", "%g" % (100 * TOLERANCE[0])),
                (("Contact pair 1",), "Friction coefficient", "%g" % mu)]

    def contrast(c):
        return [(("Body 1", "Material 1"), "Young's modulus", "1e9"),
                (("Body 2", "Material 1"), "Young's modulus", "%g" % (1e9 * c))]

    def gap(g):
        # the steel cylinder (E = 2.1e5 MPa) lifted off both walls by g
        return [(("Body 1", "Material 1"), "Young's modulus", "2.1e11"),
                (("Body 1", "Placement"), "Translation", "%g, %g" % (2.18 + g, 2.18 + g))]

    def mesh(level):
        return [(("Body 1", "Mesh"), "Global refinements", str(level)),
                (("Body 1", "Mesh"), "Local refinements", "0")]

    full = [
        ("cylinder", "floating cylinder in a corner (2D, SMALSE-M)", "cylinder.prm",
         "E", "MPa", [1, 10, 100, 1e4, 1e6, 1e8], cylinder),
        ("gap", "floating steel cylinder (E = 2.1e5 MPa) at a gap g from both walls",
         "cylinder.prm", "g", "m", [0, 1, 10, 99], gap),
        ("brick", "brick, orthotropic Tresca, 4 x 8 x 4 (3D ellipses)", "brick.prm",
         "phi", "Pa", [10, 30, 100, 500], brick),
        ("orthotropic", "brick, slip bounds (10, 10/r) Pa, 4 x 8 x 4", "brick.prm",
         "r", "-", [1, 10, 100, 1e3, 1e4], orthotropic),
        ("coulomb", "floating block, Coulomb (3D discs, fixed point, SMALSE-M)",
         "coulomb_block.prm", "mu", "-", [0.1, 0.2, 0.3, 0.5, 1, 2], coulomb),
        ("contrast", "two bodies, Tresca, E2/E1 (2D, SMALSE-M)", "two_bodies_contact.prm",
         "E2/E1", "-", [1, 10, 1e2, 1e3, 1e4, 1e5, 1e6], contrast),
        ("mesh", "Hertz 2D, uniform refinement (bounds)", "hertz_2d.prm",
         "level", "-", [3, 4, 5, 6, 7], mesh),
    ]
    if not quick:
        return full
    pick = {"cylinder": [10, 1e6], "coulomb": [0.1]}
    return [(s[0], s[1], s[2], s[3], s[4], pick[s[0]], s[6]) for s in full if s[0] in pick]


def make_input(root, scenario_input, edits, solver, args):
    """The run's input: the unedited .prm of ROOT/inputs/ and its `--set'
    arguments (the common QP settings, then the scenario's edits)."""
    common = [(("Output",), "Output folder", "out"),
              (("Output",), "Write VTU", "false"),
              (("QP solver",), "Solver", solver),
              (("QP solver",), "Tolerance", "%g" % args.tolerance),
              (("QP solver",), "Maximum iterations", str(args.max_iterations)),
              (("QP solver",), "Stagnation window", "1000")]
    settings = ["/".join(path + (name,)) + "=" + value
                for path, name, value in common + edits]
    return os.path.join(root, "inputs", scenario_input), settings


def outcome(case_dir):
    """The record of one run from run.json, statistics.json and log.txt."""
    run = json.load(open(os.path.join(case_dir, "run.json")))
    record = {"exit_code": run["exit_code"], "timeout": run["timeout"],
              "wall_time_s": run["wall_time_s"]}
    stats_file = os.path.join(case_dir, "out", "statistics.json")
    log = open(os.path.join(case_dir, "log.txt"), errors="replace").read()
    if run["timeout"]:
        record["status"] = "timeout"
        return record
    if not os.path.exists(stats_file):
        lines = [l.strip() for l in log.splitlines() if l.strip()]
        errors = [l for l in lines if l.startswith("Error") or "error" in l.lower()]
        record["message"] = (errors[-1] if errors else (lines[-1] if lines else ""))[:300]
        record["status"] = "n/a" if "only bound and box" in log else "error"
        return record
    stats = json.load(open(stats_file))
    contact = stats["contact"]
    solves = contact["qp_solves"]
    last = solves[-1]
    record.update({
        "status": "converged" if contact["converged"] else "failed",
        "reason": contact["reason"],
        "qp_reason": last["reason"],
        "n_qp_solves": len(solves),
        "iterations": sum(q["iterations"] for q in solves),
        "hessian_products": sum(q["hessian_products"] for q in solves),
        "outer_iterations": sum(q["iterations_by_kind"]["outer"] for q in solves),
        "final_criterion": last["final_criterion"],
        "kkt": last["kkt"],
        "norm_b": last["norm_b"],
        "qp_time_s": contact.get("qp_wall_time_s"),
        "coulomb_changes": contact.get("coulomb_changes", []),
        "n_multipliers": contact["n_multipliers"],
        "n_dofs": sum(b["n_dofs"] for b in stats["bodies"]),
        # the contact force (normal + tangential, summed over pairs): the
        # matrix compares it between solvers (non-unique Coulomb solutions)
        "contact_force": [sum(p["normal_force"] for p in contact["pairs"])] +
        [sum(p["tangential_force"][k] for p in contact["pairs"])
         for k in range(len(contact["pairs"][0]["tangential_force"]))],
    })
    if "attempts" in last:
        record["attempts"] = [{"solver": a["solver"], "reason": a["reason"],
                               "iterations": a["iterations"],
                               "final_criterion": a["final_criterion"]}
                              for a in last["attempts"]]
        record["chosen_solver"] = last.get("chosen_solver", "")
        record["fall_backs"] = sum(len(q.get("attempts", [])) - 1 for q in solves)
        # every QP (Coulomb iterate) in which the chain fell back
        record["fall_back_solves"] = [
            {"qp": k + 1, "chosen_solver": q.get("chosen_solver", ""),
             "attempts": [{"solver": a["solver"], "reason": a["reason"],
                           "iterations": a["iterations"],
                           "final_criterion": a["final_criterion"]}
                          for a in q["attempts"]]}
            for k, q in enumerate(solves) if len(q.get("attempts", [])) > 1]
    return record


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("program")
    parser.add_argument("root")
    parser.add_argument("bench_dir")
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--tolerance", type=float, default=1e-6)
    parser.add_argument("--max-iterations", type=int, default=10000)
    parser.add_argument("--time-limit", type=float, default=300.0)
    parser.add_argument("--solvers", default=None)
    parser.add_argument("--scenarios", default=None)
    args = parser.parse_args()
    TOLERANCE[0] = args.tolerance
    solvers = (args.solvers or ("mprgp auto" if args.quick else SOLVERS)).split()
    chosen = args.scenarios.split() if args.scenarios else None
    os.makedirs(args.bench_dir, exist_ok=True)
    run_case = os.path.join(args.root, "postprocess", "run_case.py")
    load = open("/proc/loadavg").read().split()[:3]
    start = time.time()
    results = {"command": " ".join(sys.argv), "tolerance": args.tolerance,
               "max_iterations": args.max_iterations, "time_limit_s": args.time_limit,
               "load_average_start": load, "cores": os.cpu_count(),
               "started": time.strftime("%Y-%m-%d %H:%M:%S"), "solvers": solvers,
               "scenarios": []}
    n_run = 0
    for key, title, prm, label, unit, values, edits in scenarios(args.quick):
        if chosen and key not in chosen:
            continue
        scenario = {"key": key, "title": title, "input": "inputs/" + prm,
                    "parameter": label, "unit": unit, "rows": []}
        for value in values:
            row = {"value": value, "cases": {}}
            for solver in solvers:
                case_dir = os.path.join(args.bench_dir, key, "%s_%s" % (fmt(value), solver))
                os.makedirs(case_dir, exist_ok=True)
                path, settings = make_input(args.root, prm, edits(value), solver, args)
                # the command line, kept to skip a case already run
                text = "\n".join([path] + settings) + "\n"
                args_file = os.path.join(case_dir, "case.args")
                fresh = os.path.exists(os.path.join(case_dir, "run.json")) and \
                    os.path.exists(args_file) and open(args_file).read() == text
                if not fresh:
                    n_run += 1
                    with open(args_file, "w") as f:
                        f.write(text)
                    for name in ("run.json",):
                        if os.path.exists(os.path.join(case_dir, name)):
                            os.remove(os.path.join(case_dir, name))
                    subprocess.run(["rm", "-rf", os.path.join(case_dir, "out")], check=True)
                    print("bench_stability: %-11s %s = %-6g %-8s ... " % (key, label, value, solver),
                          end="", flush=True)
                    subprocess.run(["/usr/bin/python3", run_case, args.program, case_dir,
                                    path, str(args.time_limit), "--"] +
                                   [a for setting in settings for a in ("--set", setting)],
                                   check=True)
                row["cases"][solver] = outcome(case_dir)
            scenario["rows"].append(row)
        results["scenarios"].append(scenario)
    results["load_average_end"] = open("/proc/loadavg").read().split()[:3]
    results["wall_time_s"] = time.time() - start
    out_file = os.path.join(args.bench_dir, "stability.json")
    if n_run == 0 and os.path.exists(out_file):
        # nothing was run: the timing and load are those of the run that
        # produced the outcomes
        old = json.load(open(out_file))
        for key in ("started", "load_average_start", "load_average_end", "wall_time_s"):
            if key in old:
                results[key] = old[key]
    with open(out_file, "w") as f:
        json.dump(results, f, indent=1)
    print("bench_stability: %d scenarios in %.0f s, outcomes in %s"
          % (len(results["scenarios"]), results["wall_time_s"],
             os.path.join(args.bench_dir, "stability.json")))


if __name__ == "__main__":
    main()
