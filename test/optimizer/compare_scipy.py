#!/usr/bin/env python3
"""The Optimizer's differential evolution against scipy.optimize.differential_evolution.

Same strategy (rand/1/bin, immediate updating, Latin-hypercube start, F 0.8, CR 0.9,
population 15 per dimension, no polishing, no early stop) and the same budget of
evaluations, on sphere, Rosenbrock and Rastrigin in 2, 5 and 10 dimensions over SEEDS seeds.
Passes if our median best value is within 1.5x of scipy's (or better; values below 1e-8
count as equal). Prints a Markdown table; writes a JUnit result.

    compare_scipy.py CHECK_BINARY RESULT_XML [--per-dim N] [--seeds N]
"""
import argparse
import multiprocessing
import os
import statistics
import subprocess
import sys
import time

import numpy as np
from scipy.optimize import differential_evolution

FUNCTIONS = {
    "sphere": (lambda x: float(np.sum(x * x)), (-5.12, 5.12)),
    "rosenbrock": (lambda x: float(np.sum(100 * (x[1:] - x[:-1] ** 2) ** 2 + (1 - x[:-1]) ** 2)), (-5, 10)),
    "rastrigin": (lambda x: float(10 * len(x) + np.sum(x * x - 10 * np.cos(2 * np.pi * x))), (-5.12, 5.12)),
}
SLACK = 1e-8


def scipy_best(name, dims, seed, budget):
    f, (low, high) = FUNCTIONS[name]
    popsize = 15  # scipy's multiplier: 15 * dims members, as ours
    generations = budget // (popsize * dims) - 1  # the first generation is the initial population
    res = differential_evolution(f, [(low, high)] * dims, strategy="rand1bin", maxiter=max(0, generations),
                                 popsize=popsize, mutation=0.8, recombination=0.9, seed=seed, tol=0, atol=0,
                                 polish=False, init="latinhypercube", updating="immediate")
    return float(res.fun)


def scipy_best_of(job):
    return scipy_best(*job)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("check")
    ap.add_argument("result")
    ap.add_argument("--per-dim", type=int, default=1500)
    ap.add_argument("--seeds", type=int, default=11)
    a = ap.parse_args()

    t0 = time.monotonic()
    ours = {}
    out = subprocess.run([a.check, str(a.per_dim), str(a.seeds)], check=True, capture_output=True, text=True).stdout
    for line in out.splitlines():
        name, dims, seed, best = line.split()
        ours.setdefault((name, int(dims)), []).append(float(best))
    t_ours = time.monotonic() - t0

    rows, failures = [], []
    t0 = time.monotonic()
    # scipy's runs are independent and single-threaded: one process per core
    jobs = [(name, dims, seed, a.per_dim * dims) for (name, dims) in sorted(ours) for seed in range(1, a.seeds + 1)]
    with multiprocessing.Pool(os.cpu_count() or 1) as pool:
        results = pool.map(scipy_best_of, jobs)
    by_problem = {}
    for (name, dims, _, _), best in zip(jobs, results):
        by_problem.setdefault((name, dims), []).append(best)
    for (name, dims), values in sorted(ours.items()):
        theirs = by_problem[(name, dims)]
        m_ours, m_theirs = statistics.median(values), statistics.median(theirs)
        ok = m_ours <= 1.5 * m_theirs + SLACK
        ratio = "-" if m_theirs < SLACK and m_ours < SLACK else f"{m_ours / m_theirs:.2f}x" if m_theirs > 0 else "-"
        rows.append(f"| {name} | {dims} | {a.per_dim * dims} | {m_ours:.3g} ({min(values):.3g}–{max(values):.3g}) | "
                    f"{m_theirs:.3g} ({min(theirs):.3g}–{max(theirs):.3g}) | {ratio} | {'ok' if ok else 'WORSE'} |")
        if not ok:
            failures.append(f"{name} in {dims} dimensions: median {m_ours:.3g}, scipy {m_theirs:.3g}")
    t_scipy = time.monotonic() - t0

    print(f"Differential evolution (rand/1/bin, F 0.8, CR 0.9, 15 members per dimension, Latin hypercube start,")
    print(f"immediate updating, no polish), {a.seeds} seeds each, budget {a.per_dim} evaluations per dimension;")
    print(f"best value found (minimising): median (min–max). APEX {t_ours:.1f} s, scipy {t_scipy:.1f} s in all ({os.cpu_count()} processes).\n")
    print("| function | dims | budget | APEX | scipy | APEX / scipy | |\n|---|---|---|---|---|---|---|")
    print("\n".join(rows))
    with open(a.result, "w") as x:
        x.write('<?xml version="1.0" encoding="UTF-8"?>\n')
        x.write(f'<testsuite name="optimizer" tests="1" failures="{1 if failures else 0}">\n')
        x.write('  <testcase classname="Optimizer" name="DifferentialEvolutionWithin1_5xOfScipy">\n')
        if failures:
            x.write('    <failure message="%s"/>\n' % "; ".join(failures).replace('"', "'"))
        x.write("  </testcase>\n</testsuite>\n")
    if failures:
        print("\n".join(failures), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
