#!/usr/bin/env python3
"""Runs one input of dualcontact under mpirun with 1 and more processes
and asserts that the answers agree.

Usage: compare_ranks.py DUALCONTACT MPIRUN INPUT.prm WORKDIR [TOLERANCE]
                        [--ranks=1,2,4] [--method-N=none|tfeti ...]
                        [--same-folder] [--reference-set=KEY=VALUE ...]

The runs (1 and 2 processes unless --ranks says otherwise; the first
count must be 1) must converge (exit 0, contact.converged = 1).  Each run
with N > 1 processes is compared with the 1-process run.  Asserted, with
relative tolerance TOLERANCE (default 1e-8) for the reals:
  - per contact pair: normal force, tangential force, max pressure;
    the active sets: n_nodes, n_separated, n_stick, n_slip exactly;
  - per body: strain energy, external work, max displacement, the
    reaction force of every support and the contact force (results.txt;
    relative to the body's largest force: a symmetry support carries
    round-off only) and the Euclidean norm of the displacement vector
    (statistics.json, bodies[].results.displacement_l2_norm);
  - the total normal force of the first pair equals the applied load
    (body_1.applied_force, its largest component: the scenes with one
    body and one pair press onto an axis-aligned plane) to TOLERANCE in
    both runs, when the scene has one body without supports (no
    reaction force) and one pair;
  - the dual QP ran on the vectors it should (statistics.json,
    contact.qp_vectors): dealii::Vector<double> on 1 process, and on
    N > 1 with the undecomposed dual and a serial stiffness solver
    (cholmod, umfpack: every process holds the whole factor; all
    multipliers on every process); on N > 1 with the undecomposed dual
    (contact.decomposition.method = none) and mumps or amg
    dealii::TrilinosWrappers::MPI::Vector, split over at least two
    processes (contact.multipliers_per_process, contact_nodes_per_process:
    N counts adding up to n_multipliers and n_nodes, two or more of them
    positive; a METIS subdomain may hold no contact node); with TFETI
    (method = tfeti) likewise (the rows of B on the processes of their
    subdomains), and the subdomains split over the processes
    (decomposition.subdomains_per_process: N counts adding up to
    n_subdomains, each positive when there are at least N subdomains),
    the glued field continuous (relative_interface_jump below TOLERANCE);
  - --method-N=none|tfeti: the dual the N-process run must have used
    (decomposition.method), e.g. --method-1=none --method-2=tfeti for an
    input with `Method = automatic';
  - the N-process run wrote one piece of every body per process
    (body_N_rank_R.vtu) and solution.pvtu refers to all of them, and one
    piece of every contact surface per process (contact_N_rank_R.vtu, the
    slave faces of the cells the process owns), listed in contact_N.pvtu
    (which solution.pvd lists), together holding all n_nodes contact nodes
    and as many faces as the 1-process run's contact_N.vtu, with the same
    integral of pressure_Pa (ParaView's Integrate Variables) to TOLERANCE.
With --reference-set=KEY=VALUE (repeatable), the reference is one more
1-process run with `--set KEY=VALUE' (e.g. `Decomposition/Mesh
distribution=replicated' against an input with a distributed mesh), and
every run of --ranks, the 1-process one included, is compared with it.
With --same-folder, the input is then run again into one folder with the
process counts in decreasing order (4, 2, 1): after each run the folder
holds exactly the files of that run (the list `.dualcontact_files'), no
piece of a process that did not run (a stale body_1_rank_3.vtu beside a
2-process solution.pvtu would show the old scene in ParaView).
The input's QP tolerance must be well below TOLERANCE (the runs differ by
round-off in the stiffness solves, and the QP stops at its tolerance).
"""
import json
import os
import re
import shutil
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                "..", "..", "postprocess"))
import contact_vtu  # noqa: E402


def read_results(path):
    values = {}
    with open(path) as f:
        for line in f:
            if line.startswith("#") or "=" not in line:
                continue
            key, value = line.split("=", 1)
            values[key.strip()] = [float(v) for v in value.split(",")]
    return values


def run(app, mpirun, prm, workdir, ranks, folder=None, settings=(),
        name=None):
    if folder is None:
        folder = os.path.join(workdir, name or f"np{ranks}")
        shutil.rmtree(folder, ignore_errors=True)
        os.makedirs(folder)
    env = dict(os.environ)
    env.update({"OMPI_ALLOW_RUN_AS_ROOT": "1",
                "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
                "OMPI_MCA_rmaps_base_oversubscribe": "1",
                "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"})
    command = [mpirun, "--allow-run-as-root", "--oversubscribe", "-np",
               str(ranks), app, os.path.abspath(prm)]
    for setting in settings:
        command += ["--set", setting]
    start = time.time()
    process = subprocess.run(command, cwd=folder, env=env,
                             capture_output=True, text=True)
    seconds = time.time() - start
    print(f"--- {ranks} process(es), {seconds:.2f} s: {' '.join(command)}")
    print(process.stdout)
    if process.returncode != 0:
        print(process.stderr)
        sys.exit(f"FAIL: the run with {ranks} process(es) exited with "
                 f"{process.returncode}")
    output = None
    for line in process.stdout.splitlines():
        m = re.match(r"Output written to `(.*)/':", line)
        if m:
            output = os.path.join(folder, m.group(1))
    if output is None:
        sys.exit("FAIL: no `Output written to' line")
    results = read_results(os.path.join(output, "results.txt"))
    with open(os.path.join(output, "statistics.json")) as f:
        statistics = json.load(f)
    return output, results, statistics


def main():
    arguments = [a for a in sys.argv[1:] if not a.startswith("--")]
    counts = [1, 2]
    methods = {}
    for a in sys.argv[1:]:
        if a.startswith("--ranks="):
            counts = [int(n) for n in a[len("--ranks="):].split(",")]
        m = re.match(r"--method-(\d+)=(none|tfeti)$", a)
        if m:
            methods[int(m.group(1))] = m.group(2)
    if counts[0] != 1 or len(counts) < 2:
        sys.exit("compare_ranks.py: --ranks must start with 1 and name more")
    app, mpirun, prm, workdir = arguments[0:4]
    tolerance = float(arguments[4]) if len(arguments) > 4 else 1e-8
    reference_settings = [a[len("--reference-set="):] for a in sys.argv[1:]
                          if a.startswith("--reference-set=")]
    runs = [run(app, mpirun, prm, workdir, ranks) for ranks in counts]
    if reference_settings:
        # every run against the reference, the 1-process one too
        runs.insert(0, run(app, mpirun, prm, workdir, 1,
                           settings=reference_settings, name="reference"))
        counts = [1] + counts
    failures = 0

    def check(ok, text):
        nonlocal failures
        print(("  ok   " if ok else "  FAIL ") + text)
        failures += 0 if ok else 1

    out1, r1, s1 = runs[0]
    check(s1["contact"]["qp_vectors"] == "dealii::Vector<double>",
          f"1 process: the QP ran on {s1['contact']['qp_vectors']}")
    for ranks, (_, _, s) in zip(counts[1 if reference_settings else 0:],
                                runs[1 if reference_settings else 0:]):
        if ranks in methods:
            method = s["contact"]["decomposition"]["method"]
            check(method == methods[ranks],
                  f"{ranks} process(es): the dual was {method}, expected "
                  f"{methods[ranks]}")
    for ranks, (out2, r2, s2) in zip(counts[1:], runs[1:]):
        print(f"--- 1 process{' (reference)' if reference_settings else ''}"
              f" against {ranks} processes")
        compare(check, tolerance, ranks, (out1, r1, s1), (out2, r2, s2))

    if "--same-folder" in sys.argv[1:]:
        same_folder(check, app, mpirun, prm, workdir,
                    counts[1 if reference_settings else 0:])

    print("all checks passed" if failures == 0 else "FAILED")
    sys.exit(0 if failures == 0 else 1)


def same_folder(check, app, mpirun, prm, workdir, counts):
    """Runs into one folder with decreasing process counts; after each,
    the folder holds the run's files and nothing else."""
    folder = os.path.join(workdir, "same_folder")
    shutil.rmtree(folder, ignore_errors=True)
    os.makedirs(folder)
    for ranks in sorted(counts, reverse=True):
        print(f"--- {ranks} process(es) into {folder}")
        output, _, _ = run(app, mpirun, prm, workdir, ranks, folder)
        with open(os.path.join(output, ".dualcontact_files")) as f:
            listed = set(line.strip() for line in f if line.strip())
        present = set(n for n in os.listdir(output) if not n.startswith("."))
        check(present == listed, f"{ranks} process(es) into one folder: it "
              f"holds the {len(listed)} files of the run; extra "
              f"{sorted(present - listed)}, missing {sorted(listed - present)}")
        stale = [n for n in present
                 if re.search(r"_rank_(\d+)\.vtu$", n) and
                 (ranks == 1 or
                  int(re.search(r"_rank_(\d+)", n).group(1)) >= ranks)]
        check(not stale, f"{ranks} process(es) into one folder: no piece of "
              f"another process count {sorted(stale)}")


def compare(check, tolerance, ranks, first, second):
    """Checks of one N-process run against the 1-process run (check()
    counts the failures)."""
    (out1, r1, s1), (out2, r2, s2) = first, second
    check(s1["mpi_processes"] == 1 and s2["mpi_processes"] == ranks,
          f"mpi_processes: {s1['mpi_processes']}, {s2['mpi_processes']}")
    check(r1["contact.converged"] == [1] and r2["contact.converged"] == [1],
          "both contact solves converged")
    c2 = s2["contact"]
    per_process = c2.get("multipliers_per_process", [])
    nodes_per_process = c2.get("contact_nodes_per_process", [])
    n_nodes = sum(v[0] for k, v in r2.items()
                  if re.match(r"pair_\d+\.n_nodes$", k))
    decomposition = c2.get("decomposition", {"method": "none"})
    serial = {b["stiffness_solver"]["name"] for b in s2.get("bodies", [])
              if "stiffness_solver" in b} <= {"cholmod", "umfpack"}
    if ranks == 1:
        # a 1-process run against the reference: the answers only
        pass
    elif decomposition["method"] == "none" and serial:
        # a serial solver: every process holds the whole factor, and the
        # QP runs replicated, as on one process
        check(c2.get("qp_vectors") == "dealii::Vector<double>"
              and per_process == [c2["n_multipliers"]],
              f"{ranks} processes, serial stiffness solver: the QP ran "
              f"replicated on {c2.get('qp_vectors')}, multipliers per "
              f"process {per_process} (of {c2['n_multipliers']})")
    else:
        # the multipliers on distributed vectors, split over the processes
        # (undecomposed: by contact node; TFETI: by the subdomains' rows)
        check(c2.get("qp_vectors") == "dealii::TrilinosWrappers::MPI::Vector"
              and len(per_process) == ranks
              and sum(1 for n in per_process if n > 0) >= 2
              and sum(per_process) == c2["n_multipliers"]
              and len(nodes_per_process) == ranks
              and sum(nodes_per_process) == n_nodes,
              f"{ranks} processes: the QP ran on {c2.get('qp_vectors')}, "
              f"multipliers per process {per_process} (of "
              f"{c2['n_multipliers']}), contact nodes per process "
              f"{nodes_per_process} (of {n_nodes:g})")
    if decomposition["method"] == "tfeti":
        subdomains = decomposition.get("subdomains_per_process", [])
        n_subdomains = decomposition["n_subdomains"]
        check(len(subdomains) == ranks
              and sum(subdomains) == n_subdomains
              and (n_subdomains < ranks or min(subdomains) > 0),
              f"{ranks} processes, TFETI: subdomains per process "
              f"{subdomains} (of {n_subdomains})")
        jump = decomposition["relative_interface_jump"]
        check(jump <= tolerance, f"{ranks} processes, TFETI: relative "
              f"interface jump {jump:.2e}")

    exact = re.compile(r"pair_\d+\.n_(nodes|separated|stick|slip|contact)$")
    real = re.compile(r"(pair_\d+\.(normal_force|tangential_force|"
                      r"max_pressure)|body_\d+\.(strain_energy|"
                      r"external_work|max_displacement|contact_force|"
                      r"reaction_force\.boundary_\d+))$")
    force = re.compile(r"body_(\d+)\.(contact_force|reaction_force\."
                       r"boundary_\d+)$")

    def body_force_scale(body):
        # a body's forces against the largest of them: a support that
        # carries nothing (a symmetry plane) holds round-off of the others
        prefix = f"body_{body}."
        return max([max(abs(v) for v in r1[k]) for k in r1
                    if k.startswith(prefix) and k.endswith("force")
                    or k.startswith(prefix + "reaction_force.")] + [1e-300])
    for key in sorted(r1):
        if exact.match(key):
            check(r1[key] == r2[key], f"{key}: {r1[key][0]:g} and "
                  f"{r2[key][0]:g}")
        elif real.match(key):
            a, b = r1[key], r2[key]
            scale = max(max(abs(v) for v in a), 1e-300)
            if force.match(key):
                scale = body_force_scale(force.match(key).group(1))
            diff = max(abs(x - y) for x, y in zip(a, b)) / scale
            check(diff <= tolerance, f"{key}: relative difference {diff:.2e}"
                  f" (values {a[0]:.12e}, ...)")
    for b1, b2 in zip(s1["bodies"], s2["bodies"]):
        n1 = b1["results"]["displacement_l2_norm"]
        n2 = b2["results"]["displacement_l2_norm"]
        diff = abs(n1 - n2) / n1
        check(diff <= tolerance, f"{b1['name']}: |u| {n1:.12e}, relative "
              f"difference {diff:.2e}")

    supported = any(k.startswith("body_1.reaction_force") for k in r1)
    if "pair_1.normal_force" in r1 and "pair_2.normal_force" not in r1 \
            and "body_2.n_dofs" not in r1 and not supported:
        for n, r in ((1, r1), (ranks, r2)):
            load = max(abs(v) for v in r["body_1.applied_force"])
            force = r["pair_1.normal_force"][0]
            diff = abs(force - load) / load
            check(diff <= tolerance, f"{n} process(es): normal force "
                  f"{force:.12e} = applied load {load:.12e}, relative "
                  f"difference {diff:.2e}")

    if ranks == 1:
        return
    n_bodies = int(r2["n_bodies"][0])
    with open(os.path.join(out2, "solution.pvtu")) as f:
        pvtu = f.read()
    for body in range(1, n_bodies + 1):
        for rank in range(ranks):
            name = f"body_{body}_rank_{rank}.vtu"
            check(os.path.isfile(os.path.join(out2, name)) and name in pvtu,
                  f"{ranks} processes: {name} written and in solution.pvtu")

    with open(os.path.join(out2, "solution.pvd")) as f:
        pvd = f.read()
    pair = 1
    while f"pair_{pair}.n_nodes" in r2:
        record = f"contact_{pair}.pvtu"
        path = os.path.join(out2, record)
        check(os.path.isfile(path) and record in pvd,
              f"{ranks} processes: {record} written and in solution.pvd")
        if not os.path.isfile(path):
            pair += 1
            continue
        with open(path) as f:
            master = f.read()
        for rank in range(ranks):
            name = f"contact_{pair}_rank_{rank}.vtu"
            check(os.path.isfile(os.path.join(out2, name)) and name in master,
                  f"{ranks} processes: {name} written and in {record}")
        points, _ = contact_vtu.read_contact_nodes(path)
        check(len(points) == r2[f"pair_{pair}.n_nodes"][0],
              f"{ranks} processes: the pieces of contact pair {pair} hold "
              f"{len(points)} contact nodes, n_nodes = "
              f"{r2[f'pair_{pair}.n_nodes'][0]:g}")
        pieces = contact_vtu.read_grid(path)
        whole = contact_vtu.read_grid(os.path.join(out1, f"contact_{pair}.vtu"))
        check(pieces.GetNumberOfCells() == whole.GetNumberOfCells(),
              f"{ranks} processes: {pieces.GetNumberOfCells()} faces in the "
              f"pieces, {whole.GetNumberOfCells()} on 1 process")
        f1 = contact_vtu.integrate(whole)["pressure_Pa"]
        f2 = contact_vtu.integrate(pieces)["pressure_Pa"]
        diff = abs(f2 - f1) / abs(f1)
        check(diff <= tolerance, f"{ranks} processes: integral of pressure_Pa"
              f" {f2:.12e}, 1 process {f1:.12e}, relative difference "
              f"{diff:.2e}")
        pair += 1

if __name__ == "__main__":
    main()
