"""Compare catena and CableDyn on cases/benchmarks/riser-airy-wave.toml.

Usage: python compare.py CATENA_RESULTS.h5 CABLEDYN_OUT_ROOT
(needs numpy and h5py; CABLEDYN_OUT_ROOT is what `cabledyn riser-airy-wave.dat ROOT` wrote).
"""
import sys
import numpy as np
import h5py

h5, root = sys.argv[1], sys.argv[2]
f = h5py.File(h5, "r")
t = f["dynamic/time"][:]
w = t >= 120.0 - 1e-9
arc = f["static/arc"][:]
m = f["dynamic/bending_moment"][:][w]
tt = f["dynamic/top_tension"][:][w]
tension = f["dynamic/effective_tension"][:][w]


def table(path):
    rows = [l.split() for l in open(path) if l.strip() and not l.startswith(("#", "CableDyn", "(", "Node", "Time"))]
    head = next(l.split() for l in open(path) if l.startswith(("Time", "Node")))
    return head, np.array(rows, dtype=float)


head, out = table(root + ".out")
tc = out[:, 0]
wc = tc >= 120.0 - 1e-9
col = {h: i for i, h in enumerate(head)}
rh, rng = table(root + ".Line1.range.out")
rc = {h: i for i, h in enumerate(rh)}

def pct(a, b):
    return 100.0 * (a - b) / b

print("quantity | catena | CableDyn | difference")
print("---|---|---|---")
ft = out[wc, col["FairTen1"]]
print(f"top tension mean (kN) | {tt.mean()/1e3:.2f} | {ft.mean()/1e3:.2f} | {pct(tt.mean(), ft.mean()):+.3f} %")
print(f"top tension range (kN) | {np.ptp(tt)/1e3:.3f} | {np.ptp(ft)/1e3:.3f} | {pct(np.ptp(tt), np.ptp(ft)):+.1f} %")
tdp = out[wc, col["TDP1s"]]
# |M| ranges along the line (CableDyn reports |M| = EI*kappa)
am = np.abs(m)
cat_range = am.max(0) - am.min(0)
cd_arc = rng[:, rc["ArcLength"]]
cd_range = rng[:, rc["BendMomentMax"]] - rng[:, rc["BendMomentMin"]]
cd_tr = rng[:, rc["TensionMax"]] - rng[:, rc["TensionMin"]]
cat_tr = tension.max(0) - tension.min(0)
for lo, hi, name in [(0, 300, "wave zone (arc 0-300 m)"), (1000, 1400, "touchdown zone (arc 1000-1400 m)")]:
    a = (arc >= lo) & (arc <= hi)
    b = (cd_arc >= lo) & (cd_arc <= hi)
    ia, ib = np.argmax(np.where(a, cat_range, -1)), np.argmax(np.where(b, cd_range, -1))
    print(f"largest |M| range, {name} (kN·m) | {cat_range[ia]/1e3:.3f} at {arc[ia]:.0f} m | {cd_range[ib]/1e3:.3f} at {cd_arc[ib]:.0f} m | {pct(cat_range[ia], cd_range[ib]):+.1f} %")
it = np.argmax(cd_tr)
print(f"largest tension range (kN) | {cat_tr.max()/1e3:.3f} at {arc[np.argmax(cat_tr)]:.0f} m | {cd_tr.max()/1e3:.3f} at {cd_arc[it]:.0f} m | {pct(cat_tr.max(), cd_tr.max()):+.1f} %")
