#!/usr/bin/env python3
"""catena's extreme-value fits against scipy's on the same data (validation/design-checks.md).

Reads a results file and the extremes.json that `catena extremes RESULTS.h5 --out DIR --start S`
wrote from it; rebuilds each channel's record from the file as catena's reader does, its
up-crossing peaks (the largest value between successive up-crossings of the mean) and its block
maxima, and fits them with scipy.stats (weibull_min with the location fixed at 0, gumbel_r: both
maximum likelihood), then prints both and the relative differences and fails beyond 1e-4.

usage: compare_scipy.py RESULTS.h5 EXTREMES.json START
"""
import json
import sys

import h5py
import numpy as np
from scipy import stats


def record(f, name):
    if name == "top_tension":
        return 1.0, f["dynamic/top_tension"][...]
    if name == "least_tension":
        return -1.0, f["dynamic/effective_tension"][...].min(axis=1)
    if name == "sag_moment":
        return -1.0, f["dynamic/bending_moment"][...].min(axis=1)
    if name == "utilisation":
        return 1.0, f["design_check/utilisation"][...].max(axis=1)
    raise SystemExit(f"unknown channel {name}")


def peaks(y, level):
    out, cur = [], None
    for a, b in zip(y[:-1], y[1:]):
        if a < level <= b:
            if cur is not None:
                out.append(cur)
            cur = b
        elif cur is not None:
            cur = max(cur, b)
    return np.array(out)


def main(h5, ext, start):
    start = float(start)
    worst = 0.0
    with h5py.File(h5, "r") as f:
        t = f["dynamic/time"][...]
        dt = t[1] - t[0]
        first = np.searchsorted(t, start - 1e-9)
        for e in json.load(open(ext)):
            sign, x = record(f, e["channel"])
            y = sign * x[first:]
            mean = y.mean()
            ex = peaks(y, mean) - mean
            ex = ex[ex > 0]
            k, _, lam = stats.weibull_min.fit(ex, floc=0)
            w = e["weibull"][0]
            block = int(round(e["gumbel"][0] / dt))
            n = len(y) // block
            maxima = y[: n * block].reshape(n, block).max(axis=1)
            mu, beta = stats.gumbel_r.fit(maxima)
            g = e["gumbel"][1]
            rows = [
                ("Weibull shape", w["shape"], k),
                ("Weibull scale", w["scale"], lam),
                ("Gumbel location", g["location"], mu),
                ("Gumbel scale", g["scale"], beta),
            ]
            print(f"{e['channel']}: {len(ex)} peaks, {n} blocks of {block * dt:.0f} s")
            for name, a, b in rows:
                rel = abs(a / b - 1)
                worst = max(worst, rel)
                print(f"  {name:16s} catena {a:.6e}  scipy {b:.6e}  ({rel:.1e})")
    print(f"largest relative difference {worst:.1e}")
    if worst > 1e-4:
        sys.exit("catena and scipy differ beyond 1e-4")


if __name__ == "__main__":
    main(*sys.argv[1:])
