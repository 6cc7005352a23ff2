"""Compares catena's steel lazy wave (cases/lazy-wave/cabledyn-heave.toml) with CableDyn 0.3.0's run of
lazy-wave.dat: statics (top and anchor tension, touchdown, the sag and hog bends' heights, x and
moments) and the heave (top tension range, touchdown range, the range of moment at the bends).

Usage: python compare_lazy_wave.py CATENA_OUT_DIR CABLEDYN_ROOT   (numpy, h5py)
CABLEDYN_ROOT is the root given to CableDyn (its ROOT.static.out, ROOT.out, ROOT.Line1.range.out).
CableDyn's moment is EI·κ, unsigned; its Z is from the surface (catena's z = Z + 1000 m)."""
import sys

import h5py
import numpy as np


def table(path):
    """The rows of a CableDyn output whose every field is a number."""
    rows = []
    for line in open(path):
        try:
            rows.append([float(v) for v in line.split()])
        except ValueError:
            continue
    return np.array([r for r in rows if r])


def bends(z, arc, lo, mid, hi):
    """The sag bend (the lowest point in [lo, mid]) and the hog bend (the highest in [sag, hi])."""
    idx = np.flatnonzero((arc >= lo) & (arc <= mid))
    i_sag = idx[np.argmin(z[idx])]
    after = np.flatnonzero((arc > arc[i_sag]) & (arc <= hi))
    i_hog = after[np.argmax(z[after])]
    return i_sag, i_hog


out, root = sys.argv[1], sys.argv[2]
with h5py.File(f"{out}/results.h5") as f:
    s = f["static"]
    arc, x, z = s["arc"][:], s["x"][:], s["z"][:]
    te, mom = s["effective_tension"][:], s["bending_moment"][:]
    rmin, rmax = f["ranges/bending_moment/min"][:], f["ranges/bending_moment/max"][:]
    top = f["dynamic/top_tension"][:]
    t = f["dynamic/time"][:]
    tdp = f["dynamic/touchdown_arc"][:]
st = table(f"{root}.static.out")
c_arc, c_x, c_z, c_t, c_m = st[:, 2], st[:, 3], st[:, 5] + 1000.0, st[:, 6], st[:, 8]
dyn = table(f"{root}.out")
rng = table(f"{root}.Line1.range.out")

# Both lists run from the top (CableDyn's End A); the sag bend lies above the hog bend's arc.
i_sag, i_hog = bends(z, arc, 900.0, 1400.0, 1700.0)
j_sag, j_hog = bends(c_z, c_arc, 900.0, 1400.0, 1700.0)
w = t >= 50.0
cw = dyn[:, 0] >= 50.0
rows = [
    ("static top tension (kN)", te[0] / 1e3, c_t[0] / 1e3),
    ("static anchor tension (kN)", te[-1] / 1e3, c_t[-1] / 1e3),
    ("static touchdown arc length (m; CableDyn's stretched)", tdp[0], dyn[0, 3]),
    ("sag bend height (m)", z[i_sag], c_z[j_sag]),
    ("sag bend x (m)", x[i_sag], c_x[j_sag]),
    ("hog bend height (m)", z[i_hog], c_z[j_hog]),
    ("hog bend x (m)", x[i_hog], c_x[j_hog]),
    ("|moment| at the sag bend (kN·m)", abs(mom[i_sag]) / 1e3, c_m[j_sag] / 1e3),
    ("|moment| at the hog bend (kN·m)", abs(mom[i_hog]) / 1e3, c_m[j_hog] / 1e3),
    ("heave: top tension min (kN)", top[w].min() / 1e3, dyn[cw, 1].min() / 1e3),
    ("heave: top tension max (kN)", top[w].max() / 1e3, dyn[cw, 1].max() / 1e3),
    ("heave: touchdown arc range (m)", np.ptp(tdp[w]), np.ptp(dyn[cw, 3])),
    ("heave: |moment| range at the sag bend (kN·m)", (rmax[i_sag] - rmin[i_sag]) / 1e3, (rng[j_sag, 9] - rng[j_sag, 8]) / 1e3),
    ("heave: |moment| range at the hog bend (kN·m)", (rmax[i_hog] - rmin[i_hog]) / 1e3, (rng[j_hog, 9] - rng[j_hog, 8]) / 1e3),
]
print(f"| quantity | catena | CableDyn 0.3.0 | difference |\n|---|---|---|---|")
for name, a, b in rows:
    print(f"| {name} | {a:.2f} | {b:.2f} | {100 * (a / b - 1):+.2f} % |")
