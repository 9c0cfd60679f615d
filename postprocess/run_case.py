#!/usr/bin/env python3
"""Runs one benchmark case of dualcontact and records how it went.

Usage: run_case.py PROGRAM CASE_DIR INPUT.prm [TIME_LIMIT_S] [PROCESSES]
                   [-- ARGUMENTS...]

Runs PROGRAM INPUT.prm ARGUMENTS... (e.g. --set "QP solver/Tolerance=1e-6")
in CASE_DIR (stdout and stderr to CASE_DIR/log.txt), under `mpirun -np
PROCESSES' when PROCESSES > 1, and writes CASE_DIR/run.json: exit code (0
converged, 2 the contact solver failed, other: error), whether the time
limit stopped it, wall time [s], the peak resident memory [MB] (of the
largest process: getrusage of the children, which under mpirun is the
largest rank), the number of processes and the load average when it
started.  Prints a one-line summary.
"""
import json
import os
import resource
import shutil
import subprocess
import sys
import time


def main():
    argv = sys.argv[1:]
    extra = []
    if "--" in argv:
        extra = argv[argv.index("--") + 1:]
        argv = argv[:argv.index("--")]
    program, case_dir, prm = argv[0:3]
    limit = float(argv[3]) if len(argv) > 3 and float(argv[3]) > 0 else None
    processes = int(argv[4]) if len(argv) > 4 else 1
    if not (os.path.isfile(program) and os.access(program, os.X_OK)):
        sys.exit(f"run_case.py: the program `{program}' does not exist or "
                 "is not executable (BIN_DIR?)")
    command = [program, prm] + extra
    env = dict(os.environ)
    if processes > 1:
        command = [shutil.which("mpirun"), "--allow-run-as-root",
                   "--oversubscribe", "-np", str(processes)] + command
        env.update({"OMPI_ALLOW_RUN_AS_ROOT": "1",
                    "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
                    "OMPI_MCA_rmaps_base_oversubscribe": "1"})
    load = open("/proc/loadavg").read().split()[:3]
    start = time.time()
    timeout = False
    with open(os.path.join(case_dir, "log.txt"), "w") as log:
        try:
            code = subprocess.run(command, cwd=case_dir, stdout=log, env=env,
                                  stderr=subprocess.STDOUT, timeout=limit).returncode
        except subprocess.TimeoutExpired:
            code, timeout = None, True
    wall = time.time() - start
    # the children are run one at a time, so the maximum over all children
    # is this run's peak
    peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024.0
    record = {"exit_code": code, "timeout": timeout, "wall_time_s": wall,
              "peak_memory_MB": peak, "processes": processes,
              "load_average": load}
    with open(os.path.join(case_dir, "run.json"), "w") as f:
        json.dump(record, f, indent=2)
    if timeout:
        print("stopped after %.0f s" % wall)
    else:
        print("exit %d, %.1f s, %.0f MB peak, load %s" % (code, wall, peak, load[0]))


if __name__ == "__main__":
    main()
