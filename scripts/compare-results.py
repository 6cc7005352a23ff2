#!/usr/bin/env python3
"""Compares two regression batteries (scripts/battery.sh) dataset by dataset: every float dataset of
every results.h5 to the bit, and prints, for any that differ, the largest difference relative to the
dataset's largest magnitude. summary.json is compared without its wall times.

Usage: python3 scripts/compare-results.py OUT_A OUT_B   (needs h5py and numpy)
Exit status 1 when anything differs.
"""
import json, os, sys
import h5py, numpy as np

a_dir, b_dir = sys.argv[1], sys.argv[2]
differ = 0
for name in sorted(os.listdir(a_dir)):
    fa = os.path.join(a_dir, name, 'results.h5')
    fb = os.path.join(b_dir, name, 'results.h5')
    if not os.path.isfile(fa):
        continue
    if not os.path.isfile(fb):
        print(f'{name}: no results.h5 in {b_dir}'); differ += 1; continue
    with h5py.File(fa, 'r') as A, h5py.File(fb, 'r') as B:
        paths = []
        A.visititems(lambda p, o: paths.append(p) if isinstance(o, h5py.Dataset) else None)
        bad, same = [], 0
        for p in paths:
            if p not in B:
                bad.append(f'{p}: missing'); continue
            x, y = A[p][()], B[p][()]
            if isinstance(x, np.ndarray) and x.dtype.kind == 'f':
                if x.shape != y.shape:
                    bad.append(f'{p}: shape {x.shape} vs {y.shape}'); continue
                if np.array_equal(x.view(np.uint64 if x.dtype == np.float64 else np.uint32),
                                  y.view(np.uint64 if y.dtype == np.float64 else np.uint32)):
                    same += 1; continue
                scale = np.nanmax(np.abs(x)) if x.size else 0.0
                d = np.nanmax(np.abs(x - y)) if x.size else 0.0
                bad.append(f'{p}: max |diff| {d:.3e} ({d / scale if scale else 0:.2e} of max |x|)')
            elif not np.array_equal(x, y):
                bad.append(f'{p}: differs')
            else:
                same += 1
    sa = json.load(open(os.path.join(a_dir, name, 'summary.json')))
    sb = json.load(open(os.path.join(b_dir, name, 'summary.json')))
    def strip(v):
        if isinstance(v, dict):
            return {k: strip(x) for k, x in v.items() if 'seconds' not in k and 'per_second' not in k and k not in ('wall_time', 'timing', 'version')}
        if isinstance(v, list):
            return [strip(x) for x in v]
        return v
    if strip(sa) != strip(sb):
        keys = [k for k in set(sa) | set(sb) if strip(sa.get(k)) != strip(sb.get(k))]
        bad.append(f'summary.json differs in {sorted(keys)}')
    print(f'{name}: {same} datasets identical' + (''.join('\n  ' + b for b in bad) if bad else ''))
    differ += bool(bad)
print('identical' if not differ else f'{differ} case(s) differ')
sys.exit(1 if differ else 0)
