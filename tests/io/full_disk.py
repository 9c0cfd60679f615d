#!/usr/bin/python3
"""Writing onto a full file system (issue 49): a small tmpfs filled up to a
few KB, then
  - dualcontact writing a scene's output into a new folder on it, and into
    a folder that holds an earlier run's results.txt;
  - fclibsolve --write onto it, over an existing file;
must fail with exit code 1 and one line naming the file and the cause (No
space left on device), and leave nothing behind: no temporary, no lock
file, no folder the run created; the earlier files intact.

Needs root (mount -t tmpfs); where mounting is impossible it prints why and
exits with 77, which CTest counts as skipped (SKIP_RETURN_CODE).

    full_disk.py DUALCONTACT FCLIBSOLVE PRM FCLIB_FILE WORKDIR
"""
import os
import shutil
import subprocess
import sys

SKIP = 77
dualcontact, fclibsolve, prm, fclib_file, work = sys.argv[1:6]
failures = 0


def check(what, ok, value=""):
    global failures
    print("%-4s %s %s" % ("ok" if ok else "FAIL", what, value))
    if not ok:
        failures += 1


def fill(mount, leave):
    """Fill the file system at mount up to @p leave bytes."""
    filler = os.path.join(mount, "filler")
    if os.path.exists(filler):
        os.remove(filler)
    info = os.statvfs(mount)
    free = info.f_bavail * info.f_frsize
    with open(filler, "wb") as out:
        out.write(b"x" * max(0, free - leave))


def tree(folder):
    """Every file and folder below folder, relative to it."""
    found = []
    for path, dirs, files in os.walk(folder):
        for name in dirs + files:
            found.append(os.path.relpath(os.path.join(path, name), folder))
    return sorted(found)


def run(command):
    proc = subprocess.run(command, cwd=work, capture_output=True, text=True,
                          errors="replace", timeout=300,
                          env=dict(os.environ, OMP_NUM_THREADS="1",
                                   OPENBLAS_NUM_THREADS="1"))
    lines = [line for line in proc.stderr.strip().splitlines() if line]
    return proc.returncode, lines


if os.geteuid() != 0:
    print("skipped: mounting a tmpfs needs root")
    sys.exit(SKIP)
shutil.rmtree(work, ignore_errors=True)
mount = os.path.join(os.path.abspath(work), "full")
os.makedirs(mount)
mounted = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=200k", "tmpfs",
                          mount], capture_output=True, text=True)
if mounted.returncode != 0:
    print("skipped: cannot mount a tmpfs: " + mounted.stderr.strip())
    sys.exit(SKIP)
try:
    # dualcontact into a new folder and into one with an earlier result
    os.makedirs(os.path.join(mount, "earlier"))
    with open(os.path.join(mount, "earlier", "results.txt"), "w") as out:
        out.write("an earlier run\n")
    for folder in ("new", "earlier"):
        fill(mount, 12 << 10)
        before = tree(mount)
        code, lines = run([dualcontact, prm, "--set",
                           "Output/Output folder=" + os.path.join(mount, folder)])
        last = lines[-1] if lines else ""
        check("dualcontact into `%s': exit code 1" % folder, code == 1, code)
        check("dualcontact into `%s': the file and the cause named" % folder,
              ("`" + os.path.join(mount, folder) + "/") in last and
              "No space left on device" in last, last)
        check("dualcontact into `%s': nothing left behind" % folder,
              tree(mount) == before, tree(mount))
    with open(os.path.join(mount, "earlier", "results.txt")) as f:
        check("the earlier results.txt intact", f.read() == "an earlier run\n")

    # fclibsolve --write over an existing file
    target = os.path.join(mount, "sol.hdf5")
    with open(target, "w") as out:
        out.write("earlier\n")
    fill(mount, 12 << 10)
    before = tree(mount)
    code, lines = run([fclibsolve, fclib_file, "--max-iter", "50",
                       "--coulomb-max-iter", "3", "--write", target])
    check("fclibsolve --write: exit code 1", code == 1, code)
    check("fclibsolve --write: one line", len(lines) == 1, lines)
    last = lines[-1] if lines else ""
    check("fclibsolve --write: the file and the cause named",
          ("`" + target + "'") in last and "No space left on device" in last,
          last)
    check("fclibsolve --write: no temporary left", tree(mount) == before,
          tree(mount))
    with open(target) as f:
        check("fclibsolve --write: the earlier file intact",
              f.read() == "earlier\n")
finally:
    subprocess.run(["umount", mount])
sys.exit(1 if failures else 0)
