#!/usr/bin/env python3
"""B1, the bridge pier, with the report's settings (inputs/bridge_pier_primal.prm:
release of every negative multiplier at once, relative Uzawa test 1e-5, step
factor 1.9), by P-LL(1), the cheapest variant: it converges in fewer than
MAX_UZAWA Uzawa iterations (measured 6,169 at level 0 on 2026-11-27; the
report: 527-565 at a tolerance it does not state), on the report's 10
contact constraints, and its first CGC solve starts on the facet of all 10.

usage: check_bridge_report.py DUALCONTACT INPUT WORKDIR"""
import json, os, shutil, subprocess, sys

MAX_UZAWA = 8000

app, prm, work = (os.path.abspath(a) for a in sys.argv[1:4])
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
proc = subprocess.run([app, prm, "--set", "Primal solver/Version=pcg1",
                       "--set", "Output/Output folder=out",
                       "--set", "Output/Write VTU=false"],
                      cwd=work, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                      text=True)
stats_file = os.path.join(work, "out", "statistics.json")
if not os.path.exists(stats_file):
    print(proc.stdout[-2000:])
    sys.exit("no statistics.json: the run failed")
p = json.load(open(stats_file))["contact"]["primal"]
failures = 0


def check(ok, what, value):
    global failures
    print("  %s %s: %s" % ("ok  " if ok else "FAIL", what, value))
    failures += 0 if ok else 1


check(p["converged"], "converged", p["reason"])
check(p["uzawa_iterations"] < MAX_UZAWA,
      "Uzawa iterations < %d" % MAX_UZAWA, p["uzawa_iterations"])
check(p["n_constraints"] == 10, "contact constraints (report: NCP 10)",
      p["n_constraints"])
outer = p["first_cgc"]["outer"]
check(len(outer) > 0 and outer[0]["active"] == 10,
      "first CGC starts on the facet of all 10 constraints",
      outer[0]["active"] if outer else "no outer iteration")
print("all checks passed" if failures == 0 else "FAILED")
sys.exit(1 if failures else 0)
