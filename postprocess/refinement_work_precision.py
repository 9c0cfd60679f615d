#!/usr/bin/python3
"""Contact-zone refinement against uniform refinement on the Hertz scenes:
errors against the closed form, work-precision charts, and the factors of
dofs and time at which the contact-zone refinement reaches the accuracy of
the finest uniform level (issue 6, "Model no more than a scene needs").

Run with /usr/bin/python3 (Debian's numpy and matplotlib).  Used by
scripts/bench_refinement.

    refinement_work_precision.py [--figure STEM] [--markdown FILE]
                                 [--command TEXT]
                                 CASE:KIND:LEVEL:INPUT.prm:OUTPUT_FOLDER ...

Each argument names one finished run: a case (`Hertz 2D', `Hertz 3D'), its
kind (`uniform' or `adaptive'), its level (uniform: the refinement level;
adaptive: the number of contact refinement cycles), the .prm that was run
(its first line is the `# Hertz:' line) and its output folder.  The errors
are those of postprocess/hertz_convergence.py (err a: contact half-width /
radius, err p0: peak pressure, L2 nodal: relative L2 error of the nodal
pressures, L2 interp (2D): of their piecewise-linear interpolant); the time
is the sum of the phase wall times of statistics.json, which for an
adaptive run is every cycle's (all solves, refinements and output).

Factors: for each error, the finest uniform level's |error| e_U (dofs N_U,
time T_U) is the target; the first adaptive run (fewest cycles) with
|error| <= e_U has N_A dofs and took T_A; the factors are N_U / N_A and
T_U / T_A (> 1: the adaptive run is cheaper).  `not reached' when no
adaptive run gets there.

--figure STEM writes STEM_2d.png, STEM_3d.png (one per case: error against
dofs and against wall time, one panel pair per error, uniform and adaptive
curves); --markdown FILE replaces the text between `<!-- refinement begin
-->' and `<!-- refinement end -->' of FILE by the tables (with --command
naming what produced them).
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import hertz_convergence  # noqa: E402

ERRORS = [("a_error", "err a (half-width / radius)"),
          ("peak_error", "err p0 (peak pressure)"),
          ("l2_nodal", "L2 nodal (pressure)"),
          ("l2_interp", "L2 interp (pressure, 2D)")]


def errors_of(row):
    return [(key, label) for key, label in ERRORS if key in row]


def factors(uniform, adaptive):
    """{error: (e_U, N_U, T_U, level, N_A, T_A, dof factor, time factor)}
    with level None when no adaptive run reaches e_U."""
    finest = max(uniform, key=lambda r: r["n_dofs"])
    result = {}
    for key, _ in errors_of(finest):
        target = abs(finest[key])
        reached = None
        for row in sorted(adaptive, key=lambda r: r["level"]):
            if abs(row[key]) <= target:
                reached = row
                break
        if reached is None:
            result[key] = (target, finest["n_dofs"], finest["wall_time"],
                           None, None, None, None, None)
        else:
            result[key] = (target, finest["n_dofs"], finest["wall_time"],
                           reached["level"], reached["n_dofs"],
                           reached["wall_time"],
                           finest["n_dofs"] / reached["n_dofs"],
                           finest["wall_time"] / reached["wall_time"])
    return finest, result


def runs_table(rows):
    keys = errors_of(rows[0])
    columns = ["kind", "level / cycles", "dofs", "in contact", "h [m]"] + \
        [label.split(" (")[0] for _, label in keys] + \
        ["QP products", "time [s]"]
    lines = ["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]
    for row in rows:
        cells = [row["kind"], str(row["level"]), str(row["n_dofs"]),
                 str(row["n_contact"]), f"{row['h']:.3g}"]
        cells += [f"{row[k]:+.2e}" if k in ("a_error", "peak_error")
                  else f"{row[k]:.2e}" for k, _ in keys]
        cells += [str(row["hessian_products"]), f"{row['wall_time']:.2f}"]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def factors_table(finest, result):
    lines = [f"Target: the finest uniform level ({finest['level']}, "
             f"{finest['n_dofs']} dofs, {finest['wall_time']:.2f} s).", "",
             "| error | uniform (finest) | adaptive reaches it at | dofs "
             "factor | time factor |", "|---|---|---|---|---|"]
    for key, label in ERRORS:
        if key not in result:
            continue
        target, _, _, level, n_a, t_a, fd, ft = result[key]
        if level is None:
            lines.append(f"| {label} | {target:.2e} | not reached | - | - |")
        else:
            lines.append(f"| {label} | {target:.2e} | {level} cycles, {n_a} "
                         f"dofs, {t_a:.2f} s | {fd:.1f} | {ft:.1f} |")
    return "\n".join(lines)


def draw(stem, case, rows):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    keys = errors_of(rows[0])
    fig, axes = plt.subplots(2, len(keys), figsize=(4.2 * len(keys), 7.5),
                             squeeze=False)
    for j, (key, label) in enumerate(keys):
        for i, (x_key, x_label) in enumerate([("n_dofs", "dofs"),
                                              ("wall_time",
                                               "wall time [s]")]):
            ax = axes[i][j]
            for kind, style in (("uniform", "o-"), ("adaptive", "s-")):
                sel = sorted([r for r in rows if r["kind"] == kind],
                             key=lambda r: r["level"])
                if not sel:
                    continue
                x = [r[x_key] for r in sel]
                y = [max(abs(r[key]), 1e-16) for r in sel]
                ax.loglog(x, y, style, label=kind +
                          (" (levels)" if kind == "uniform" else
                           " (cycles)"))
                for r, xi, yi in zip(sel, x, y):
                    ax.annotate(str(r["level"]), (xi, yi), fontsize=7,
                                textcoords="offset points", xytext=(3, 3))
            ax.set_xlabel(x_label)
            ax.set_ylabel("|" + label + "|")
            ax.grid(True, which="both", alpha=0.3)
            if i == 0 and j == 0:
                ax.legend(fontsize=8)
    fig.suptitle(f"{case}: contact-zone refinement against uniform "
                 "refinement (error against the closed form)")
    fig.tight_layout()
    path = f"{stem}_{case.split()[-1].lower()}.png"
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def main(argv):
    stem = markdown = command = None
    runs = []
    args = list(argv)
    while args:
        arg = args.pop(0)
        if arg in ("--figure", "--markdown", "--command"):
            if not args:
                sys.exit(f"{arg} needs a value\n{__doc__}")
            value = args.pop(0)
            if arg == "--figure":
                stem = value
            elif arg == "--markdown":
                markdown = value
            else:
                command = value
        else:
            parts = arg.split(":")
            if len(parts) != 5 or parts[1] not in ("uniform", "adaptive"):
                sys.exit(f"bad run `{arg}'\n{__doc__}")
            runs.append(parts)
    if not runs:
        sys.exit(__doc__)

    cases = {}
    for case, kind, level, prm, folder in runs:
        row = hertz_convergence.evaluate(prm, folder)
        row["kind"] = kind
        row["level"] = int(level)
        cases.setdefault(case, []).append(row)

    text = []
    for case, rows in cases.items():
        uniform = [r for r in rows if r["kind"] == "uniform"]
        adaptive = [r for r in rows if r["kind"] == "adaptive"]
        text.append(f"### {case}\n")
        text.append(f"Closed form for the applied load: a = {rows[0]['a']:.5g}"
                    f" m, p0 = {rows[0]['p0']:.5g} Pa.\n")
        text.append(runs_table(uniform + adaptive) + "\n")
        if uniform and adaptive:
            finest, result = factors(uniform, adaptive)
            text.append(factors_table(finest, result) + "\n")
        if stem:
            path = draw(stem, case, rows)
            text.append(f"![{case}](figures/{os.path.basename(path)})\n")
            print(f"wrote {path}")
    body = "\n".join(text)
    print(body)
    if markdown:
        with open(markdown) as f:
            doc = f.read()
        begin, end = "<!-- refinement begin -->", "<!-- refinement end -->"
        if begin not in doc or end not in doc:
            sys.exit(f"{markdown} has no `{begin}' ... `{end}' markers")
        head, rest = doc.split(begin, 1)
        _, tail = rest.split(end, 1)
        produced = f"Produced by: {command}\n\n" if command else ""
        with open(markdown, "w") as f:
            f.write(head + begin + "\n\n" + produced + body + "\n" + end +
                    tail)
        print(f"updated {markdown}")


if __name__ == "__main__":
    main(sys.argv[1:])
