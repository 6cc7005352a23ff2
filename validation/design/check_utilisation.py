#!/usr/bin/env python3
"""An independent evaluation of the DNV-ST-F201 combined-loading utilisation from what a run
recorded (validation/design-checks.md).

Reads results.h5 of `catena run` on cases/scr1000/design-100yr-*.toml: the recorded bending moment,
effective tension and height at every record and node, the static ones (the functional load
effects), and compares the utilisation computed here, written from the standard's formulas with
numpy alone, with catena's `/design_check/utilisation` at every record and node.

usage: check_utilisation.py RESULTS.h5 [RESULTS.h5 ...]
"""
import sys

import h5py
import numpy as np

# The case's pipe and check (cases/scr1000/design-100yr-*.toml).
D, T_NOM, T_CORR = 0.228, 0.0254, 0.003
SMYS, SMTS, ALPHA_U = 448e6, 531e6, 0.96
P_D, RHO_C, RHO_W, G, DEPTH = 15e6, 726.0, 1025.0, 9.80665, 1000.0
GAMMA_SC, GAMMA_M, GAMMA_F, GAMMA_E = 1.14, 1.15, 1.1, 1.3
E, NU, F0, A_FAB = 210e9, 0.3, 0.005, 1.0


def collapse(t):
    fy = SMYS * ALPHA_U
    p_el = 2 * E * (t / D) ** 3 / (1 - NU**2)
    p_p = fy * A_FAB * 2 * t / D
    # The cubic's root below min(p_el, p_p), by numpy's polynomial roots.
    c = F0 * D / t
    roots = np.roots([1.0, -p_el, -(p_p**2 + p_el * p_p * c), p_el * p_p**2])
    real = roots[np.abs(roots.imag) < 1e-6 * np.abs(roots.real)].real
    return real[(real > 0) & (real < min(p_el, p_p))].min()


def utilisation(m, te, z, m_f, te_f):
    t = T_NOM - T_CORR
    fy, fu = SMYS * ALPHA_U, SMTS * ALPHA_U
    head = np.maximum(DEPTH - z, 0.0)
    p_e = RHO_W * G * head
    p_ld = P_D + RHO_C * G * head
    pb = 2 / np.sqrt(3) * 2 * t / (D - t) * min(fy, fu / 1.15)
    dp = p_ld - p_e
    qh = np.where(dp > 0, dp / pb * 2 / np.sqrt(3), 0.0)
    dt = D / t
    beta = np.where(dt < 15, 0.4 + qh, np.where(dt <= 60, (0.4 + qh) * (60 - dt) / 45, 0.0))
    ac = (1 - beta) + beta * fu / fy
    mk = fy * ac * (D - t) ** 2 * t
    tk = fy * ac * np.pi * (D - t) * t
    md = GAMMA_F * m_f + GAMMA_E * (m - m_f)
    ted = GAMMA_F * te_f + GAMMA_E * (te - te_f)
    g = GAMMA_SC * GAMMA_M
    r_int = dp / pb
    internal = (g * (np.abs(md) / mk * np.sqrt(np.maximum(1 - r_int**2, 0)) + (ted / tk) ** 2)) ** 2 + (g * r_int) ** 2
    external = (g * (np.abs(md) / mk + (ted / tk) ** 2)) ** 2 + (g * (-dp) / collapse(t)) ** 2
    return np.where(dp >= 0, internal, external)


def main(paths):
    worst = 0.0
    for p in paths:
        with h5py.File(p, "r") as f:
            m = f["dynamic/bending_moment"][...]
            te = f["dynamic/effective_tension"][...]
            z = f["dynamic/z"][...]
            m_f = f["static/bending_moment"][...]
            te_f = f["static/effective_tension"][...]
            u = f["design_check/utilisation"][...]
            umax = f["design_check/utilisation_max"][...]
            time = f["dynamic/time"][...]
            arc = f["dynamic/arc"][...]
        mine = utilisation(m, te, z, m_f[None, :], te_f[None, :])
        rel = np.abs(mine / u - 1).max()
        worst = max(worst, rel)
        k, i = np.unravel_index(np.argmax(mine), mine.shape)
        after = time >= 200.0
        print(
            f"{p}: {u.shape[0]} records x {u.shape[1]} nodes; largest difference {rel:.2e}; "
            f"largest recorded utilisation {mine[after].max():.5f} at {arc[i]:.1f} m, t {time[k]:.1f} s; "
            f"catena's every-step largest {umax.max():.5f} at {arc[np.argmax(umax)]:.1f} m"
        )
    if worst > 1e-9:
        sys.exit(f"the utilisations differ by {worst:.2e} (tolerance 1e-9)")


if __name__ == "__main__":
    main(sys.argv[1:])
