#!/usr/bin/env python3
"""`Stiffness solver/Solver = automatic' under MPI on a scene without
contact (inputs/cantilever.prm): cholmod, a whole factor on every process,
while its copies on the machine fit `Decomposition/Memory limit'; mumps,
spread over the processes, beyond (driver::Scene::choose_solver).

Usage: solver_choice.py DUALCONTACT MPIRUN INPUT.prm WORKDIR

Asserted: 1 process, any limit: cholmod; 2 processes, the default limit:
cholmod; 2 processes, a limit of 0.001 MB: mumps, and the log's body line
says why; the strain energy of every run equal to the 1-process one to
1e-8 relative (statistics.json bodies[0].stiffness_solver.name,
results.txt body_1.strain_energy).
"""
import json
import os
import re
import shutil
import subprocess
import sys


def run(app, mpirun, prm, workdir, ranks, limit):
    folder = os.path.join(workdir, f"np{ranks}_limit{limit}")
    shutil.rmtree(folder, ignore_errors=True)
    os.makedirs(folder)
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1",
               OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OMP_NUM_THREADS="1",
               OPENBLAS_NUM_THREADS="1")
    command = [mpirun, "--allow-run-as-root", "--oversubscribe", "-np",
               str(ranks), app, os.path.abspath(prm),
               "--set", "Output/Output folder=out",
               "--set", "Output/Write VTU=false"]
    if limit is not None:
        command += ["--set", f"Decomposition/Memory limit={limit}"]
    process = subprocess.run(command, cwd=folder, env=env,
                             capture_output=True, text=True)
    print(f"--- {' '.join(command)}: exit {process.returncode}")
    if process.returncode != 0:
        print(process.stdout, process.stderr)
        sys.exit("FAIL: the run exited with %d" % process.returncode)
    with open(os.path.join(folder, "out", "statistics.json")) as f:
        statistics = json.load(f)
    energy = None
    with open(os.path.join(folder, "out", "results.txt")) as f:
        for line in f:
            m = re.match(r"body_1\.strain_energy\s*=\s*(\S+)", line)
            if m:
                energy = float(m.group(1))
    return (statistics["bodies"][0]["stiffness_solver"]["name"], energy,
            process.stdout)


def main():
    app, mpirun, prm, workdir = sys.argv[1:5]
    failures = 0

    def check(ok, text):
        nonlocal failures
        print(("  ok   " if ok else "  FAIL ") + text)
        failures += 0 if ok else 1

    one = run(app, mpirun, prm, workdir, 1, 0.001)
    check(one[0] == "cholmod", f"1 process, limit 0.001 MB: {one[0]}")
    for limit, expected in ((None, "cholmod"), (0.001, "mumps")):
        name, energy, log = run(app, mpirun, prm, workdir, 2, limit)
        what = f"2 processes, limit {limit or 'default'}"
        check(name == expected, f"{what}: {name} (expected {expected})")
        if expected == "mumps":
            check("above `Decomposition/Memory limit'" in log,
                  f"{what}: the log says why")
        difference = abs(energy - one[1]) / abs(one[1])
        check(difference < 1e-8, f"{what}: strain energy {energy:.12e}, "
              f"relative difference {difference:.1e} to 1 process")
    print("FAILED" if failures else "all checks passed")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
