"""Shared by the test scripts, the Python side of test_tools.h: a named
check that prints its value and counts failures, a run of the program with
--set overrides, and the readers of results.txt and history.csv.

Scripts import it after putting tests/ on sys.path:
    sys.path.insert(0, os.path.join(HERE, ".."))
    from script_tools import check, run_app, exit_status
"""
import csv
import os
import subprocess

failures = 0


def check(ok, what, value):
    """Print ok/FAIL, the description and the measured value."""
    global failures
    print(("ok   " if ok else "FAIL ") + what + ": " + str(value))
    if not ok:
        failures += 1


def exit_status():
    """Print the failure count; the script's exit status."""
    print("%d failure(s)" % failures)
    return 1 if failures else 0


def mpi_launcher(mpirun, np):
    """The command prefix that runs a program on NP processes (none for
    one)."""
    return ([mpirun, "--allow-run-as-root", "--oversubscribe", "-np",
             str(np)] if np > 1 else [])


def run_app(app, input_file, workdir, name, settings, launcher=(),
            label=None):
    """Run `launcher app input_file --set Output/Output folder=workdir/name
    --set S...` in workdir; check its exit status (as LABEL, default NAME)
    and return the output folder, or None (with the command and the end of
    its output printed) when it failed."""
    out = os.path.join(workdir, name)
    command = list(launcher) + [app, input_file,
                                "--set", "Output/Output folder=" + out]
    for s in settings:
        command += ["--set", s]
    result = subprocess.run(command, cwd=workdir, capture_output=True,
                            text=True)
    check(result.returncode == 0, (label or name) + ": exit status",
          result.returncode)
    if result.returncode != 0:
        print(" ".join(command))
        print(result.stdout[-3000:], result.stderr[-3000:])
        return None
    return out


def run_steps(args, name, times, settings=()):
    """run_app() of a load history: args.app on args.input in args.workdir
    with `Load steps/Step times = TIMES`, no VTU, then SETTINGS and the
    script's own --set options (args.set, if it has them)."""
    return run_app(args.app, args.input, args.workdir, name,
                   ["Output/Write VTU=false",
                    "Load steps/Step times=" + times] + list(settings)
                   + list(getattr(args, "set", [])))


def read_results(path):
    """results.txt as KEY -> list of numbers (lines that are no numbers
    left out)."""
    values = {}
    with open(path) as f:
        for line in f:
            if line.startswith("#") or "=" not in line:
                continue
            key, value = (s.strip() for s in line.split("=", 1))
            try:
                values[key] = [float(v) for v in value.split(",")]
            except ValueError:
                continue
    return values


def read_history(folder):
    """history.csv of an output folder: one dict KEY -> float per step."""
    with open(os.path.join(folder, "history.csv")) as f:
        return [{k: float(v) for k, v in row.items()}
                for row in csv.DictReader(f)]


def check_every_step_balances(rows, tolerance=1e-8):
    """Applied + reactions + contact = 0 per body at every step of a
    history (the body_N.force_imbalance columns of history.csv)."""
    imbalance = max(float(v) for r in rows for k, v in r.items()
                    if k.endswith(".force_imbalance"))
    check(imbalance <= tolerance,
          "every step: body_N.force_imbalance <= %g" % tolerance,
          "%.3e" % imbalance)
