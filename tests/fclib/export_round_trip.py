#!/usr/bin/python3
"""App-level FCLIB round trip: `dualcontact export_block.prm` writes the
scene's contact problem in both FCLIB forms with its solution; `fclibsolve`
reads each file, solves it (Coulomb fixed point, mpgp, tolerances 1e-12 /
1e-11) and compares with the stored scene solution: the contact forces must
agree to 1e-8 (relative) and both FCLIB errors be below 1e-8.

    export_round_trip.py DUALCONTACT FCLIBSOLVE PRM WORKDIR
"""
import json
import os
import shutil
import subprocess
import sys

dualcontact, fclibsolve, prm, work = sys.argv[1:5]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
subprocess.run([dualcontact, prm], cwd=work, check=True, stdout=subprocess.DEVNULL)
failures = 0
for form in ("global", "local"):
    path = os.path.join(work, "output", "contact_problem_%s.hdf5" % form)
    summary = os.path.join(work, form + ".json")
    run = subprocess.run([fclibsolve, path, "--solver", "mpgp", "--tol", "1e-12",
                          "--coulomb-tol", "1e-11", "--coulomb-max-iter", "200",
                          "--json", summary], capture_output=True, text=True)
    print(run.stdout, run.stderr)
    s = json.load(open(summary)) if os.path.exists(summary) else {}
    checks = [
        ("exit code 0", run.returncode == 0, run.returncode),
        ("form", s.get("form") == form, s.get("form")),
        ("contacts (25 nodes of a 4x4 face)", s.get("n_contacts") == 25, s.get("n_contacts")),
        ("converged", s.get("converged") is True, s.get("reason")),
        ("||r - r_scene|| / ||r_scene|| <= 1e-8", s.get("difference_to_stored", 1) <= 1e-8,
         s.get("difference_to_stored")),
        ("FCLIB error of the scene's r <= 1e-8", s.get("stored_solution_fclib_error", 1) <= 1e-8,
         s.get("stored_solution_fclib_error")),
        ("FCLIB error of fclibsolve's r <= 1e-8", s.get("fclib_error", 1) <= 1e-8, s.get("fclib_error")),
    ]
    for what, ok, value in checks:
        print("  %s %s %s: %s" % ("ok  " if ok else "FAIL", form, what, value))
        failures += not ok

# the same local problem with W kept sparse (dense by default: W = F is
# full), and bad option values: exit code 1, the option named, no output
path = os.path.join(work, "output", "contact_problem_local.hdf5")
summary = os.path.join(work, "sparse.json")
run = subprocess.run([fclibsolve, path, "--solver", "mpgp", "--tol", "1e-12",
                      "--coulomb-tol", "1e-11", "--coulomb-max-iter", "200",
                      "--storage", "sparse", "--json", summary], capture_output=True, text=True)
s = json.load(open(summary)) if os.path.exists(summary) else {}
checks = [("sparse storage: as asked", s.get("storage") == "sparse", s.get("storage")),
          ("sparse storage: ||r - r_scene|| / ||r_scene|| <= 1e-8",
           s.get("difference_to_stored", 1) <= 1e-8, s.get("difference_to_stored")),
          ("default storage of the local file is dense",
           json.load(open(os.path.join(work, "local.json"))).get("storage") == "dense", "")]
for args, word in ((["--prox", "sometimes"], "Proximal regularization"),
                   (["--storage", "diagonal"], "storage of W")):
    out = os.path.join(work, "bad.json")
    run = subprocess.run([fclibsolve, path] + args + ["--json", out], capture_output=True, text=True)
    checks.append(("%s: exit 1, names '%s', no output" % (" ".join(args), word),
                   run.returncode == 1 and word in run.stderr and not os.path.exists(out),
                   run.stderr.strip()))
for what, ok, value in checks:
    print("  %s %s: %s" % ("ok  " if ok else "FAIL", what, value))
    failures += not ok
print("all checks passed" if failures == 0 else "FAILED")
sys.exit(1 if failures else 0)
