#!/usr/bin/python3
"""Dolan-More performance profiles (Dolan and More 2002; the thesis' section 3
introduction), shared by postprocess/fclib_profiles.py and
postprocess/speed_accuracy.py.

For a set of problems P and solvers S with a cost t_ps (time, iterations,
Hessian products) of every solved run, the performance ratio is

    r_ps = t_ps / min_s t_ps        (the best solver on p has r = 1),

over the solvers that solved p.  A run that failed (or was not solved to the
required accuracy) gets r_ps = r_max, a value larger than every finite
ratio, so that its solver's curve never counts it: the profile of solver s

    rho_s(tau) = |{p : r_ps <= tau}| / |P|,   1 <= tau < r_max,

is the fraction of problems s solves within a factor tau of the best; rho_s(1)
is how often s is the fastest, rho_s just below r_max how often it solves at
all.  Problems that no solver solved are left out (no best cost to compare
with); callers say how many.  Here r_max = R_MAX_FACTOR times the largest
finite ratio over all solvers (at least 2), the convention of
postprocess/fclib_profiles.py since it was written; the charts are drawn up to
r_max, where the curves end.

Run with /usr/bin/python3 (Debian's numpy and matplotlib).
"""
import math

R_MAX_FACTOR = 2.0


def performance_ratios(costs, solvers=None):
    """costs: {problem: {solver: cost, or None for a failed run}}.

    Returns (problems, solvers, ratios, r_max, unsolved): the problems that
    at least one solver solved (sorted), the solvers (in the given order,
    else in order of appearance), ratios {solver: [r_ps or None (failed)]}
    in the order of the problems, r_max, and the problems no solver solved.
    A solver without a run on a problem counts as failed there.  Costs must
    be positive (callers clamp a zero iteration count or time to their
    resolution).
    """
    if solvers is None:
        solvers = []
        for per_solver in costs.values():
            for s in per_solver:
                if s not in solvers:
                    solvers.append(s)
    problems, unsolved = [], []
    for p in sorted(costs):
        solved = [c for c in costs[p].values() if c is not None]
        (problems if solved else unsolved).append(p)
    ratios = {s: [] for s in solvers}
    largest = 1.0
    for p in problems:
        best = min(c for c in costs[p].values() if c is not None)
        if not best > 0:
            raise ValueError("performance_ratios: problem %s has a cost %r <= 0"
                             % (p, best))
        for s in solvers:
            c = costs[p].get(s)
            if c is None:
                ratios[s].append(None)
            else:
                r = c / best
                ratios[s].append(r)
                largest = max(largest, r)
    r_max = R_MAX_FACTOR * largest
    return problems, solvers, ratios, r_max, unsolved


def profile(ratio_list, taus):
    """rho(tau) for one solver's ratios (None = failed) at every tau."""
    n = len(ratio_list)
    finite = sorted(r for r in ratio_list if r is not None)
    out = []
    for t in taus:
        k = 0
        while k < len(finite) and finite[k] <= t:
            k += 1
        out.append(k / n if n else 0.0)
    return out


def taus(r_max, n=400):
    """The abscissae of a profile chart: log-spaced from 1 to just below
    r_max (a failed run, at r_max, is never counted)."""
    top = math.log10(r_max)
    return [10 ** (top * k / n) for k in range(n)]


def draw(ax, solvers, ratios, r_max, measure, colours=None, style=None,
         title=None):
    """Draws the step curves of every solver on the axes @p ax, the x axis
    log2 from 1 to r_max, labelled with @p measure."""
    xs = taus(r_max)
    for k, s in enumerate(solvers):
        if not ratios[s]:
            continue
        kwargs = {}
        if colours is not None:
            kwargs["color"] = colours(k)
        ax.step(xs, profile(ratios[s], xs), style(s) if style else "-",
                where="post", label=s, **kwargs)
    ax.set_xscale("log", base=2)
    ax.set_xlim(1, r_max)
    ax.set_xlabel("tau (ratio to the best %s)" % measure)
    ax.set_ylabel("fraction of problems within tau")
    ax.set_ylim(0, 1.02)
    ax.grid(True, which="both", alpha=0.3)
    if title:
        ax.set_title(title)
