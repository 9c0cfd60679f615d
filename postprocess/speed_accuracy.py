#!/usr/bin/python3
"""Speed against accuracy (issue 6, charts 1-3): runs the sweeps and draws

  1. work-precision charts, error against the QP's wall time and against
     Hessian products, one curve per solver, points along mesh levels (at a
     fixed tolerance) and along solver tolerances (on a fixed mesh), for
     Hertz 2D and 3D (error against the closed form) and the brick (error
     against a reference solution at tight tolerance on the finest mesh):
     work_precision_{hertz_2d,hertz_3d,brick}.png;
  2. convergence histories, the stopping criterion relative to ||b||
     against iterations and against time, per solver, for the brick and the
     bridge pier: convergence_{brick,bridge}.png;
  3. Dolan-More performance profiles over every problem of the sweeps
     (Hertz 2D / 3D, brick, bridge, cylinder, membrane) for QP time,
     iterations and Hessian products: profile_{time,iterations,products}.png
     (postprocess/performance_profiles.py);

and writes the data behind them: speed_accuracy_runs.csv (one row per run)
and speed_accuracy_data.json (every chart's points), and Markdown tables
(speed_accuracy_tables.md).  Called by scripts/bench_speed_accuracy.

    speed_accuracy.py --bin BIN_DIR --out OUT_DIR --work WORK_DIR
                      [--quick] [--time-limit S] [--jobs N] [--root SRC]

--quick runs the QUICK configuration below (the ctest smoke test), else
FULL.  Runs go to WORK_DIR/<case>/<run>; a run whose folder holds the same
input and a run.json is not repeated (delete WORK_DIR to redo everything).
--jobs runs that many processes at once (the quick mode: most of a small
run is the program's start-up; timed sweeps should run one at a time).

The error measures (see doc/speed_accuracy.md):
  Hertz: the relative L2 error of the contact pressure against the closed
    form, nodal quadrature ("L2 nodal" of postprocess/hertz_convergence.py,
    doc/hertz.md), for the load the discretized model carries.
  brick: the relative error of the nodal contact traction (pressure and
    tangential traction, a 3-vector per contact node) against the reference
    run at the same points, sqrt(sum_i w_i |t_i - t_ref(x_i)|^2) /
    sqrt(sum_i w_i |t_ref(x_i)|^2) over the contact nodes x_i of the coarser
    mesh with its area weights w_i; the reference mesh is finer than every
    mesh of the sweep and the meshes are nested (L, 2L, L subdivisions with
    L dividing the reference's), so every contact node of a run is a node of
    the reference mesh (checked to 1e-9 of the brick's size).  Beside it the same norm of
    the contact face's displacement relative to the obstacle (slip and gap).
  Along tolerances also the algebraic error: the same traction norm against
    a run on the same mesh at a tolerance far below the sweep's (REFERENCE
    tolerance), i.e. the part of the error the solver's tolerance decides.
Time is the QP's wall time (sum over the QP solves of statistics.json): the
assembly, factorization and dual-operator set-up are the same for every
solver on a mesh and are listed in the CSV (total_time_s).
"""
import argparse
import concurrent.futures
import csv
import json
import math
import os
import re
import shutil
import subprocess
import sys
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import contact_vtu  # noqa: E402
import hertz_convergence  # noqa: E402
import performance_profiles  # noqa: E402

ALL_SOLVERS = ["mprgp", "mpgp", "mpgp-bb", "mwpgp", "spg-qp", "pbbf", "apgd"]
# MPRGP takes bound and box constraints only: not the 3D friction ellipses
ELLIPSE_SOLVERS = [s for s in ALL_SOLVERS if s != "mprgp"]

# The sweeps.  Work-precision cases: `levels' at `level_tolerance', and
# `tolerances' at `sweep_level'; `reference': (solver, tolerance) of the
# tight runs (brick: on the finest level, the error reference of every run;
# every case: on the sweep level, the algebraic error's reference).
FULL = {
    "hertz_2d": dict(input="hertz_2d.prm", refine="Global", levels=[-1, 0, 1, 2],
                     level_tolerance=1e-8, sweep_level=0,
                     tolerances=[1e-2, 1e-4, 1e-6, 1e-8, 1e-10],
                     reference=("mprgp", 1e-12), solvers=ALL_SOLVERS),
    "hertz_3d": dict(input="hertz_3d.prm", refine="Local", levels=[-2, -1, 0],
                     level_tolerance=1e-8, sweep_level=-1,
                     tolerances=[1e-2, 1e-4, 1e-6, 1e-8, 1e-10],
                     reference=("mprgp", 1e-12), solvers=ALL_SOLVERS),
    "brick": dict(input="brick.prm", levels=[2, 4, 8], level_tolerance=1e-8,
                  sweep_level=8, tolerances=[1e-2, 1e-4, 1e-6, 1e-8],
                  reference=("mpgp", 1e-11), reference_level=16,
                  solvers=ELLIPSE_SOLVERS),
    # convergence histories and profiles only
    "bridge": dict(input="bridge_pier.prm", levels=[0, 1, 2], tolerance=1e-10,
                   solvers=ALL_SOLVERS),
    "cylinder": dict(input="cylinder.prm", moduli=[1e6, 1e7, 1e8], tolerance=1e-10,
                     solvers=ALL_SOLVERS),
    "membrane": dict(sizes=[50, 100], p=0.5, tolerance=1e-6, solvers=ALL_SOLVERS),
    "history_cases": {"brick": 8, "bridge": 2},
    "max_iterations": 50000,
}
# the quick mode: two solvers that take every case
QUICK_SOLVERS = ["mpgp", "mpgp-bb"]
QUICK = {
    "hertz_2d": dict(input="hertz_2d.prm", refine="Global", levels=[-2, -1],
                     level_tolerance=1e-8, sweep_level=-1,
                     tolerances=[1e-3, 1e-8], reference=("mpgp", 1e-12),
                     solvers=QUICK_SOLVERS),
    "hertz_3d": dict(input="hertz_3d.prm", refine="Local", levels=[-3, -2],
                     level_tolerance=1e-8, sweep_level=-2,
                     tolerances=[1e-3, 1e-8], reference=("mpgp", 1e-12),
                     solvers=QUICK_SOLVERS),
    "brick": dict(input="brick.prm", levels=[1, 2], level_tolerance=1e-8,
                  sweep_level=2, tolerances=[1e-3, 1e-8],
                  reference=("mpgp", 1e-11), reference_level=4, solvers=QUICK_SOLVERS),
    "bridge": dict(input="bridge_pier.prm", levels=[0], tolerance=1e-10,
                   solvers=QUICK_SOLVERS),
    "cylinder": dict(input="cylinder.prm", moduli=[1e7], tolerance=1e-10,
                     solvers=QUICK_SOLVERS),
    "membrane": dict(sizes=[20], p=0.5, tolerance=1e-6, solvers=QUICK_SOLVERS),
    "history_cases": {"brick": 2, "bridge": 0},
    "max_iterations": 50000,
}
WORK_PRECISION_CASES = ["hertz_2d", "hertz_3d", "brick"]
# what went wrong without stopping the charts (in the data file and printed)
WARNINGS = []
MEASURES = [("qp_time_s", "QP time"), ("iterations", "iterations"),
            ("products", "Hessian products")]
LABEL = {"hertz_2d": "Hertz 2D (cylinder on a plane, half model)",
         "hertz_3d": "Hertz 3D (sphere on a plane, quarter model)",
         "brick": "steel brick, orthotropic Tresca, phi = 10",
         "bridge": "bridge pier (3 bodies, Tresca)",
         "cylinder": "floating cylinder in a corner",
         "membrane": "membrane on a stepped obstacle"}
RUN_COLUMNS = ["case", "problem", "level", "solver", "tolerance", "role", "converged",
               "reason", "final_criterion", "iterations", "products", "qp_time_s",
               "total_time_s", "process_time_s", "n_dofs", "n_multipliers",
               "error", "error_displacement", "algebraic_error", "folder"]


# --------------------------------------------------------------- inputs


def common_settings(solver, tolerance, max_iterations):
    """The `--set' arguments every run gets."""
    return ["Output/Output folder=out", "Output/Write VTU=false",
            "QP solver/Solver=%s" % solver, "QP solver/Tolerance=%r" % tolerance,
            "QP solver/Maximum iterations=%d" % max_iterations,
            # only the iteration limit (and the time limit) stop a solver, as
            # in scripts/bench_brick: a slow solver is slow, not "stagnating"
            "QP solver/Stagnation window=0"]


def value_in(path, name):
    """The value of the first `set NAME = ...' line of the .prm at PATH (the
    unedited input: the level shifts it)."""
    m = re.search(r"(?m)^\s*set %s\s*=\s*([^#\n]*)" % re.escape(name),
                  open(path).read())
    if m is None:
        raise ValueError("%s: no `%s' line" % (path, name))
    return m.group(1).strip()


def make_input(root, case, cfg, level, solver, tolerance, max_iterations):
    """The input of one run: the unedited .prm of inputs/ and the `--set'
    arguments that make the case (its level) and the solver settings."""
    path = os.path.join(root, "inputs", cfg["input"])
    settings = []
    if case.startswith("hertz"):
        name = "%s refinements" % cfg["refine"]
        value = int(value_in(path, name)) + level
        if value < 0:
            raise ValueError("%s level %d: %s < 0" % (case, level, name))
        settings.append("Body 1/Mesh/%s=%d" % (name, value))
    elif case == "brick":
        settings.append("Body 1/Mesh/Subdivisions=%d, %d, %d" % (level, 2 * level, level))
    elif case == "bridge":
        for body in (1, 2, 3):
            settings.append("Body %d/Mesh/Gmsh file=%s" % (
                body, os.path.join(root, "meshes", "bridge_pier_body%d_level%d.msh" % (body, level))))
    elif case == "cylinder":
        settings.append("Body 1/Material 1/Young's modulus=%r" % level)
    return path, settings + common_settings(solver, tolerance, max_iterations)


# ----------------------------------------------------------------- runs


class Run:
    """One run: its folder, what it is, and after execution its record."""

    def __init__(self, case, level, solver, tolerance, role, folder, text=None,
                 membrane=None):
        # text: (input .prm, its `--set' arguments) of a dualcontact run
        self.case, self.level, self.solver, self.tolerance = case, level, solver, tolerance
        self.role, self.folder, self.text, self.membrane = role, folder, text, membrane
        self.record = None

    @property
    def problem(self):
        """The profile's problem name: the case, its mesh / parameter and the
        tolerance (the same configuration for every solver)."""
        return "%s/%s/%g" % (self.case, self.level, self.tolerance)


def run_dualcontact(program, run, time_limit):
    """Runs the app unless the folder already holds this input's run."""
    os.makedirs(run.folder, exist_ok=True)
    # the command line of the run, kept to skip a run already done
    path, settings = run.text
    command = os.path.join(run.folder, "input.args")
    text = "\n".join([path] + settings) + "\n"
    done = os.path.join(run.folder, "run.json")
    if os.path.exists(done) and os.path.exists(command) and open(command).read() == text:
        return
    open(command, "w").write(text)
    for stale in (done, os.path.join(run.folder, "out")):
        if os.path.isdir(stale):
            shutil.rmtree(stale)
        elif os.path.exists(stale):
            os.remove(stale)
    arguments = [a for setting in settings for a in ("--set", setting)]
    subprocess.run(["/usr/bin/python3", os.path.join(HERE, "run_case.py"), program,
                    run.folder, path, str(time_limit), "--"] + arguments,
                   check=True, stdout=subprocess.DEVNULL)


def make_membrane(qpsolve, run):
    """Writes the membrane problem of the run (once per size); returns the
    file with qpsolve's description of it."""
    h, p = run.membrane
    problem_dir = os.path.join(os.path.dirname(run.folder), "problem_h%d_p%g" % (h, p))
    info_file = os.path.join(problem_dir, "info.json")
    if not os.path.exists(info_file):
        os.makedirs(problem_dir, exist_ok=True)
        out = subprocess.run([qpsolve, "--make-membrane", "--dir", problem_dir, "--variant",
                              "thesis", "--h", str(h), "--p", str(p)],
                             capture_output=True, text=True, check=True)
        open(info_file, "w").write(out.stdout)
    return info_file


def run_membrane(qpsolve, run, time_limit, max_iterations):
    """Makes the membrane problem (once per size) and solves it with qpsolve."""
    info = json.load(open(make_membrane(qpsolve, run)))
    os.makedirs(run.folder, exist_ok=True)
    command = [qpsolve, info["problem"], "--solver", run.solver, "--tol", repr(run.tolerance),
               "--max-iter", str(max_iterations)]
    done = os.path.join(run.folder, "result.json")
    key = os.path.join(run.folder, "command.txt")
    if os.path.exists(done) and os.path.exists(key) and open(key).read() == " ".join(command):
        return
    start = time.time()
    try:
        out = subprocess.run(command, capture_output=True, text=True, timeout=time_limit)
        result = json.loads(out.stdout) if out.returncode in (0, 2) else {
            "reason": "error: " + out.stderr.strip()[-300:], "converged": False}
    except subprocess.TimeoutExpired:
        result = {"reason": "time limit (%g s)" % time_limit, "converged": False}
    result["process_time_s"] = time.time() - start
    result["n"] = info["n"]
    json.dump(result, open(done, "w"), indent=1)
    open(key, "w").write(" ".join(command))


def read_record(run):
    """The run's numbers (a dict; 'converged' False with a reason when the
    run failed in any way)."""
    r = {"case": run.case, "problem": run.problem, "level": run.level, "solver": run.solver,
         "tolerance": run.tolerance, "role": run.role, "folder": run.folder,
         "error": None, "error_displacement": None, "algebraic_error": None}
    if run.membrane is not None:
        res = json.load(open(os.path.join(run.folder, "result.json")))
        r.update(converged=bool(res.get("converged")), reason=res.get("reason"),
                 final_criterion=res.get("final_criterion"),
                 iterations=res.get("iterations"), products=res.get("hessian_products"),
                 qp_time_s=res.get("time"), total_time_s=res.get("time"),
                 process_time_s=res.get("process_time_s"), n_dofs=res.get("n"),
                 n_multipliers=res.get("n"))
        return r
    info = json.load(open(os.path.join(run.folder, "run.json")))
    r["process_time_s"] = info["wall_time_s"]
    stats_file = os.path.join(run.folder, "out", "statistics.json")
    if info.get("timeout"):
        r.update(converged=False, reason="time limit (%.0f s)" % info["wall_time_s"])
        return r
    if not os.path.exists(stats_file):
        r.update(converged=False, reason="error exit %s (no statistics)" % info["exit_code"])
        return r
    stats = json.load(open(stats_file))
    contact = stats["contact"]
    solves = contact["qp_solves"]
    r.update(
        converged=bool(contact["converged"]) and info["exit_code"] == 0,
        reason=contact["reason"] if contact.get("reason") else
        (solves[-1]["reason"] if solves else "no QP solve"),
        final_criterion=solves[-1]["final_criterion"] if solves else None,
        iterations=sum(q["iterations"] for q in solves),
        products=sum(q["hessian_products"] for q in solves),
        qp_time_s=sum(q["wall_time"] for q in solves),
        total_time_s=sum(stats["wall_time_s"].values()),
        n_dofs=sum(b["n_dofs"] for b in stats["bodies"]),
        n_multipliers=contact["n_multipliers"])
    if r["converged"]:
        r["reason"] = "converged"
    return r


def read_contact(folder):
    """(points, traction (n x 3 or n x 2), face displacement, weights) of a
    run's contact_1.vtu: the traction is [pressure, tangential traction],
    the displacement [slip, gap]."""
    out = hertz_convergence.output_folder(folder)
    points, f = contact_vtu.read_contact_nodes(os.path.join(out, "contact_1.vtu"))

    def columns(name):
        v = f[name]
        return v.reshape(len(points), -1)
    traction = numpy.hstack([columns("pressure_Pa"), columns("tangential_traction_Pa")])
    displacement = numpy.hstack([columns("slip_m"), columns("gap_m")])
    return points, traction, displacement, f["area_weight_m2"]


def contact_error(folder, reference_folder):
    """Relative weighted l2 errors (traction, face displacement) of the run
    in @p folder against the reference run at the run's contact nodes."""
    points, t, d, w = read_contact(folder)
    rpoints, rt, rd, _ = read_contact(reference_folder)
    size = numpy.ptp(rpoints, axis=0).max()
    index = {tuple(numpy.round(p / (1e-9 * size)).astype(numpy.int64)): k
             for k, p in enumerate(rpoints)}
    match = []
    for p in points:
        k = index.get(tuple(numpy.round(p / (1e-9 * size)).astype(numpy.int64)))
        if k is None:
            # rounding may put a point just across a grid line: search
            distances = numpy.linalg.norm(rpoints - p, axis=1)
            k = int(numpy.argmin(distances))
            if distances[k] > 1e-9 * size:
                raise ValueError("%s: contact node %s is not a node of the reference %s"
                                 % (folder, p, reference_folder))
        match.append(k)
    match = numpy.array(match)

    def error(a, b):
        norm = math.sqrt(numpy.sum(w * numpy.sum(b ** 2, axis=1)))
        return math.sqrt(numpy.sum(w * numpy.sum((a - b) ** 2, axis=1))) / norm
    return error(t, rt[match]), error(d, rd[match])


# ------------------------------------------------------------- the plan


def plan(cfg, work, root):
    """Every run of the configuration."""
    runs = []
    max_it = cfg["max_iterations"]

    def add(case, level, solver, tol, role):
        c = cfg[case]
        folder = os.path.join(work, case, "L%s_%s_tol%g" % (level, solver, tol))
        if case == "membrane":
            runs.append(Run(case, level, solver, tol, role, folder, membrane=(level, c["p"])))
        else:
            runs.append(Run(case, level, solver, tol, role, folder,
                            make_input(root, case, c, level, solver, tol, max_it)))
    for case in WORK_PRECISION_CASES:
        c = cfg[case]
        seen = set()
        for level in c["levels"]:
            for s in c["solvers"]:
                add(case, level, s, c["level_tolerance"], "level")
                seen.add((level, s, c["level_tolerance"]))
        for tol in c["tolerances"]:
            for s in c["solvers"]:
                if (c["sweep_level"], s, tol) not in seen:
                    add(case, c["sweep_level"], s, tol, "tolerance")
                    seen.add((c["sweep_level"], s, tol))
        s, tol = c["reference"]
        add(case, c["sweep_level"], s, tol, "reference")
        if "reference_level" in c:
            # the error reference: finer than every mesh of the sweep
            add(case, c["reference_level"], s, tol, "reference")
    for case, key in (("bridge", "levels"), ("cylinder", "moduli"), ("membrane", "sizes")):
        c = cfg[case]
        for level in c[key]:
            for s in c["solvers"]:
                add(case, level, s, c["tolerance"], "profile")
    return runs


def execute(runs, bin_dir, time_limit, jobs, max_iterations):
    program = os.path.join(bin_dir, "dualcontact")
    qpsolve = os.path.join(bin_dir, "qpsolve")
    # the membrane problems first (the solvers of one size share its file)
    for run in runs:
        if run.membrane is not None:
            make_membrane(qpsolve, run)

    def one(run):
        if run.membrane is None:
            run_dualcontact(program, run, time_limit)
        else:
            run_membrane(qpsolve, run, time_limit, max_iterations)
        return run
    done = 0
    with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
        for run in pool.map(one, runs):
            done += 1
            if done % 10 == 0 or done == len(runs):
                print("speed_accuracy: %d / %d runs, load %s" % (
                    done, len(runs), open("/proc/loadavg").read().split()[0]), flush=True)
    for run in runs:
        run.record = read_record(run)


def evaluate_errors(runs, cfg):
    """Fills record['error'] (and 'error_displacement', 'algebraic_error')."""
    by_key = {(r.case, r.level, r.solver, r.tolerance): r for r in runs}
    for case in WORK_PRECISION_CASES:
        c = cfg[case]
        s_ref, tol_ref = c["reference"]
        same_mesh_ref = by_key[(case, c["sweep_level"], s_ref, tol_ref)]
        fine_ref = by_key.get((case, c.get("reference_level"), s_ref, tol_ref))
        usable = {}
        for name, ref in (("same mesh", same_mesh_ref), ("finest mesh", fine_ref)):
            usable[name] = ref is not None and ref.record["converged"]
            if ref is not None and not usable[name]:
                # no error against it then: said loudly, the charts lack
                # those points
                message = "%s: the %s reference run %s did not converge (%s)" % (
                    case, name, ref.folder, ref.record["reason"])
                print("speed_accuracy: WARNING " + message, flush=True)
                WARNINGS.append(message)
        for r in runs:
            if r.case != case or not r.record["converged"]:
                continue
            if case.startswith("hertz"):
                # the unedited input: its `# Hertz:' line holds the load
                r.record["error"] = hertz_convergence.evaluate(r.text[0], r.folder)["l2_nodal"]
            elif r.role != "reference" and usable["finest mesh"]:
                r.record["error"], r.record["error_displacement"] = \
                    contact_error(r.folder, fine_ref.folder)
            if r.level == c["sweep_level"] and r is not same_mesh_ref and usable["same mesh"]:
                r.record["algebraic_error"] = contact_error(r.folder, same_mesh_ref.folder)[0]


# ------------------------------------------------------------ the charts

COLOURS = {s: plt.get_cmap("tab10")(k) for k, s in enumerate(ALL_SOLVERS)}
MARKERS = {s: m for s, m in zip(ALL_SOLVERS, "osD^vP*")}


def work_precision(case, cfg, runs, out):
    """The 2 x 2 chart of a case and its data."""
    c = cfg[case]
    rows = [r.record for r in runs if r.case == case and r.role != "reference"]
    data = {"levels": {}, "tolerances": {}, "failed": [],
            "level_tolerance": c["level_tolerance"], "sweep_level": c["sweep_level"]}
    for s in c["solvers"]:
        along_levels = sorted((r for r in rows if r["solver"] == s and
                               r["tolerance"] == c["level_tolerance"] and
                               r["level"] in c["levels"]), key=lambda r: r["level"])
        along_tols = sorted((r for r in rows if r["solver"] == s and
                             r["level"] == c["sweep_level"] and
                             r["tolerance"] in c["tolerances"]),
                            key=lambda r: -r["tolerance"])
        for r in along_levels + along_tols:
            if not r["converged"] and r["problem"] + "/" + s not in data["failed"]:
                data["failed"].append(r["problem"] + "/" + s)
        data["levels"][s] = [[r["level"], r["qp_time_s"], r["products"], r["error"], r["n_dofs"]]
                             for r in along_levels if r["converged"] and r["error"] is not None]
        data["tolerances"][s] = [[r["tolerance"], r["qp_time_s"], r["products"], r["error"],
                                  r["algebraic_error"]]
                                 for r in along_tols if r["converged"] and r["error"] is not None]
    fig, axes = plt.subplots(2, 2, figsize=(12, 9))
    what = "pressure L2 error against the closed form" if case.startswith("hertz") else \
        "traction error against the reference (%d x %d x %d, %s at %g)" % (
            c["reference_level"], 2 * c["reference_level"], c["reference_level"],
            c["reference"][0], c["reference"][1])
    for row, key in enumerate(("levels", "tolerances")):
        for col, (x_index, x_label) in enumerate(((1, "QP wall time [s]"),
                                                  (2, "Hessian products"))):
            ax = axes[row][col]
            for s in c["solvers"]:
                pts = data[key][s]
                if not pts:
                    continue
                x = [p[x_index] for p in pts]
                ax.loglog(x, [p[3] for p in pts], "-", marker=MARKERS[s], color=COLOURS[s],
                          label=s, ms=5)
                if key == "tolerances":
                    alg = [(p[x_index], p[4]) for p in pts if p[4] is not None and p[4] > 0]
                    if alg:
                        ax.loglog([a[0] for a in alg], [a[1] for a in alg], ":",
                                  marker=MARKERS[s], color=COLOURS[s], ms=3, lw=1)
            # narrow ranges get labelled minor ticks: small and slanted
            ax.tick_params(axis="x", which="both", labelsize=7, labelrotation=30)
            ax.set_xlabel(x_label)
            ax.set_ylabel("relative error")
            ax.grid(True, which="both", alpha=0.3)
            if key == "levels":
                levels = ", ".join(str(v) for v in c["levels"])
                ax.set_title("along mesh levels %s, tolerance %g" % (levels, c["level_tolerance"]),
                             fontsize=9)
            else:
                tols = ", ".join("%g" % v for v in c["tolerances"])
                ax.set_title("along tolerances %s, level %s\n(solid: %s; dotted: "
                             "algebraic error against %s at %g on this mesh)"
                             % (tols, c["sweep_level"],
                                "error as above", c["reference"][0], c["reference"][1]),
                             fontsize=9)
    axes[0][0].legend(fontsize=8)
    failed = ("; failed: " + ", ".join(data["failed"])) if data["failed"] else ""
    fig.suptitle("Work-precision, %s: %s%s" % (LABEL[case], what, failed), fontsize=10)
    fig.tight_layout()
    name = os.path.join(out, "work_precision_%s.png" % case)
    fig.savefig(name, dpi=100)
    plt.close(fig)
    print("wrote", name)
    return data


def history_of(run):
    """(criterion, iterations, products, time) of the run's one QP solve."""
    stats = json.load(open(os.path.join(run.folder, "out", "statistics.json")))
    solves = stats["contact"]["qp_solves"]
    if len(solves) != 1:
        raise ValueError("%s: %d QP solves, the history chart takes one" % (run.folder, len(solves)))
    q = solves[0]
    for key in ("history", "history_time_s", "history_iterations", "history_products"):
        if key not in q:
            raise ValueError("%s: the QP record has no `%s'" % (run.folder, key))
    crit = [float(v) for v in q["history"]]
    return {"criterion": crit, "iterations": q["history_iterations"],
            "products": q["history_products"], "time_s": q["history_time_s"],
            "tolerance": q["tolerance"], "converged": q["converged"], "reason": q["reason"],
            "qp_time_s": q["wall_time"]}


def convergence(case, level, cfg, runs, out):
    c = cfg[case]
    chosen = [r for r in runs if r.case == case and r.level == level and
              r.role in ("level", "profile") and r.record.get("iterations") is not None]
    if case == "brick":
        chosen = [r for r in chosen if r.tolerance == c["level_tolerance"]]
    data = {"level": level, "solvers": {}}
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
    tol = None
    for r in sorted(chosen, key=lambda r: ALL_SOLVERS.index(r.solver)):
        h = history_of(r)
        tol = h["tolerance"]
        data["solvers"][r.solver] = h
        label = r.solver + ("" if h["converged"] else " (%s after %d iterations, %.2g s)" % (
            h["reason"], h["iterations"][-1], h["time_s"][-1]))
        for ax, key in zip(axes, ("iterations", "time_s")):
            ax.semilogy(h[key], h["criterion"], "-", color=COLOURS[r.solver], label=label, lw=1)
    # a run that stopped at its limit would squeeze the others into a corner:
    # the x range ends at 1.5 times the last converged entry, and the label
    # says how far a failed run went
    for ax, key in zip(axes, ("iterations", "time_s")):
        ends = [h[key][-1] for h in data["solvers"].values() if h["converged"]]
        if ends and any(not h["converged"] for h in data["solvers"].values()):
            ax.set_xlim(0, 1.5 * max(ends))
    for ax, xl in zip(axes, ("iterations", "time since the QP started [s]")):
        if tol:
            ax.axhline(tol, color="k", ls="--", lw=0.8)
        ax.set_xlabel(xl)
        ax.set_ylabel("stopping criterion ||g^P|| / ||b||")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=8)
    n = chosen[0].record["n_multipliers"] if chosen else 0
    where = ("%d x %d x %d" % (level, 2 * level, level)) if case == "brick" else "level %s" % level
    fig.suptitle("Convergence histories, %s, %s, %d multipliers (dashed: tolerance %g)"
                 % (LABEL[case], where, n, tol or 0), fontsize=10)
    fig.tight_layout()
    name = os.path.join(out, "convergence_%s.png" % case)
    fig.savefig(name, dpi=100)
    plt.close(fig)
    print("wrote", name)
    return data


def profiles(runs, out):
    """The three profiles over every problem of the sweeps (reference runs
    excluded)."""
    rows = [r.record for r in runs if r.role != "reference"]
    solvers = [s for s in ALL_SOLVERS if any(r["solver"] == s for r in rows)]
    problems = sorted({r["problem"] for r in rows})
    not_applicable = {s: [p for p in problems if not any(r["problem"] == p and r["solver"] == s
                                                         for r in rows)] for s in solvers}
    data = {}
    for key, label in MEASURES:
        costs = {p: {} for p in problems}
        for r in rows:
            v = r.get(key)
            if r["converged"] and v is not None:
                # a zero count or time is clamped to its resolution
                v = max(float(v), 1e-6 if key == "qp_time_s" else 1.0)
                costs[r["problem"]][r["solver"]] = v
            else:
                costs[r["problem"]][r["solver"]] = None
        solved, order, ratios, r_max, unsolved = \
            performance_profiles.performance_ratios(costs, solvers)
        data[key] = {"problems": solved, "unsolved": unsolved, "r_max": r_max,
                     "ratios": ratios,
                     "failures": {s: sum(1 for v in ratios[s] if v is None) for s in order}}
        fig, ax = plt.subplots(figsize=(8, 5))
        labels = {}
        for s in order:
            na = len(not_applicable[s])
            labels[s] = s + (" (%d n/a)" % na if na else "")
        performance_profiles.draw(ax, [labels[s] for s in order],
                                  {labels[s]: ratios[s] for s in order}, r_max, label,
                                  colours=lambda k: COLOURS[order[k]])
        ax.legend(fontsize=8, loc="lower right")
        ax.set_title("Performance profile, %s: %d problems (Hertz 2D/3D, brick, bridge, "
                     "cylinder, membrane)\nfailed / not applicable runs at r_max = %.3g"
                     % (label, len(solved), r_max), fontsize=9)
        fig.tight_layout()
        name = os.path.join(out, "profile_%s.png" % key.replace("_s", "").replace("qp_", ""))
        fig.savefig(name, dpi=100)
        plt.close(fig)
        print("wrote", name)
    return data


# ------------------------------------------------------------- tables


def fmt(v, spec):
    return "-" if v is None else spec % v


def tables(runs, cfg):
    """Markdown: one table per case, every run."""
    lines = []
    for case in WORK_PRECISION_CASES + ["bridge", "cylinder", "membrane"]:
        rows = sorted((r.record for r in runs if r.case == case),
                      key=lambda r: (r["role"] == "reference", float(r["level"]),
                                     -r["tolerance"], ALL_SOLVERS.index(r["solver"])))
        if not rows:
            continue
        what = {"cylinder": "E [Pa]", "membrane": "h"}.get(case, "level")
        lines.append("\n#### %s\n" % LABEL[case])
        lines.append("| %s | solver | tol | role | outcome | iterations | products | QP [s] "
                     "| total [s] | multipliers | error | alg. error |" % what)
        lines.append("|---|---|---|---|---|---|---|---|---|---|---|---|")
        for r in rows:
            outcome = "converged" if r["converged"] else "**%s** (%s)" % (
                r["reason"], fmt(r.get("final_criterion") if isinstance(
                    r.get("final_criterion"), (int, float)) else None, "%.1e"))
            lines.append("| %s | %s | %g | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
                r["level"], r["solver"], r["tolerance"], r["role"], outcome,
                fmt(r.get("iterations"), "%d"), fmt(r.get("products"), "%d"),
                fmt(r.get("qp_time_s"), "%.3g"), fmt(r.get("total_time_s"), "%.3g"),
                fmt(r.get("n_multipliers"), "%d"), fmt(r["error"], "%.2e"),
                fmt(r["algebraic_error"], "%.2e")))
    return "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--bin", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--work", required=True)
    parser.add_argument("--root", default=os.path.dirname(HERE))
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--time-limit", type=float, default=300.0)
    parser.add_argument("--jobs", type=int, default=1)
    a = parser.parse_args()
    cfg = QUICK if a.quick else FULL
    a.bin, a.work, a.out = (os.path.abspath(v) for v in (a.bin, a.work, a.out))
    os.makedirs(a.out, exist_ok=True)
    load_start = open("/proc/loadavg").read().split()[:3]
    start = time.time()
    runs = plan(cfg, a.work, a.root)
    print("speed_accuracy: %d runs (%s), load average %s, work folder %s" % (
        len(runs), "quick" if a.quick else "full", " ".join(load_start), a.work), flush=True)
    execute(runs, a.bin, a.time_limit, a.jobs, cfg["max_iterations"])
    evaluate_errors(runs, cfg)

    data = {"mode": "quick" if a.quick else "full",
            "load_average_start": load_start,
            "config": {k: v for k, v in cfg.items()},
            "work_precision": {}, "convergence": {}}
    for case in WORK_PRECISION_CASES:
        data["work_precision"][case] = work_precision(case, cfg, runs, a.out)
    for case, level in cfg["history_cases"].items():
        data["convergence"][case] = convergence(case, level, cfg, runs, a.out)
    data["profiles"] = profiles(runs, a.out)
    data["warnings"] = WARNINGS
    data["load_average_end"] = open("/proc/loadavg").read().split()[:3]
    data["elapsed_s"] = time.time() - start

    with open(os.path.join(a.out, "speed_accuracy_runs.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=RUN_COLUMNS, extrasaction="ignore")
        w.writeheader()
        for r in runs:
            w.writerow({k: ("" if r.record.get(k) is None else r.record.get(k))
                        for k in RUN_COLUMNS})
    with open(os.path.join(a.out, "speed_accuracy_data.json"), "w") as f:
        json.dump(data, f, indent=1)
    with open(os.path.join(a.out, "speed_accuracy_tables.md"), "w") as f:
        f.write(tables(runs, cfg))
    failed = [r.record for r in runs if not r.record["converged"]]
    print("speed_accuracy: %d runs, %d not converged%s; %.0f s, load average %s at the end"
          % (len(runs), len(failed),
             "".join("\n  %s %s: %s" % (r["problem"], r["solver"], r["reason"]) for r in failed),
             data["elapsed_s"], data["load_average_end"][0]))


if __name__ == "__main__":
    main()
