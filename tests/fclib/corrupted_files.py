#!/usr/bin/python3
"""fclibsolve on randomly corrupted copies of FCLIB files (issue 49): bytes
of a local and a global problem overwritten at random places (a fixed seed;
runs of 1 to 64 bytes, random or zero).  libfclib ends the process on any
HDF5 call that fails, printing `./src/fclib.h: 621 => ERROR: HDF5 call
failed' and naming no file; so every copy must either
  - be solved (exit 0 or 2: the damage hit numbers, or nothing that is
    read), or
  - be refused with exit code 1 and one line that names the copy's file
    (and, when FileLayout found it, the data set or group),
never end by a signal, hang, or print libfclib's or HDF5's own errors.  At
least a few copies must be refused (else the corruption missed the
structure and the test tests nothing).

    corrupted_files.py FCLIBSOLVE DATA_DIR WORKDIR [--copies N] [--seed S]
"""
import argparse
import os
import random
import shutil
import subprocess
import sys

parser = argparse.ArgumentParser()
parser.add_argument("fclibsolve")
parser.add_argument("data")
parser.add_argument("work")
parser.add_argument("--copies", type=int, default=40)
parser.add_argument("--seed", type=int, default=49)
args = parser.parse_args()

SOURCES = ["local_problem_test.hdf5",
           "LMGC_GlobalFrictionContactProblem00046.hdf5"]
shutil.rmtree(args.work, ignore_errors=True)
os.makedirs(args.work)
rng = random.Random(args.seed)
counts = {"solved": 0, "refused": 0}
failures = []
for source in SOURCES:
    original = open(os.path.join(args.data, source), "rb").read()
    for k in range(args.copies):
        data = bytearray(original)
        for _ in range(rng.randrange(1, 4)):
            length = rng.randrange(1, 65)
            at = rng.randrange(0, len(data) - length)
            fill = (bytes(length) if rng.random() < 0.3 else
                    bytes(rng.randrange(256) for _ in range(length)))
            data[at:at + length] = fill
        copy = os.path.join(args.work, "%s.%02d.hdf5" % (source[:-5], k))
        with open(copy, "wb") as out:
            out.write(data)
        try:
            proc = subprocess.run([args.fclibsolve, copy, "--max-iter", "200",
                                   "--coulomb-max-iter", "5"],
                                  capture_output=True, text=True,
                                  errors="replace", timeout=120,
                                  env=dict(os.environ, OMP_NUM_THREADS="1",
                                           OPENBLAS_NUM_THREADS="1"))
        except subprocess.TimeoutExpired:
            failures.append((copy, "no exit within 120 s"))
            continue
        lines = [line for line in proc.stderr.splitlines() if line.strip()]
        raw = [line for line in lines
               if "HDF5 call failed" in line or "HDF5-DIAG" in line]
        if proc.returncode < 0:
            failures.append((copy, "signal %d" % -proc.returncode))
        elif raw:
            failures.append((copy, "raw error: " + raw[0]))
        elif proc.returncode in (0, 2):
            counts["solved"] += 1
        elif proc.returncode == 1:
            if len(lines) == 1 and copy in lines[0]:
                counts["refused"] += 1
                print("refused %s: %s" % (os.path.basename(copy), lines[0]))
            else:
                failures.append((copy, "exit 1, message: %s" % lines))
        else:
            failures.append((copy, "exit %d: %s" % (proc.returncode, lines)))
        if not failures or failures[-1][0] != copy:
            os.remove(copy)

print("%d copies: %d solved, %d refused naming the file, %d failed"
      % (len(SOURCES) * args.copies, counts["solved"], counts["refused"],
         len(failures)))
for copy, what in failures:
    print("FAIL %s: %s" % (copy, what))
if counts["refused"] < 3:
    print("FAIL: fewer than 3 copies refused: the corruption tests nothing")
    sys.exit(1)
sys.exit(1 if failures else 0)
