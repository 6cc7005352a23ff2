"""Writes lazy_wave_motion.txt, the top motion of cases/lazy-wave/cabledyn-heave.toml for CableDyn's
`motionFile`: the heave benchmark's z = 2 r(t) sin(2πt/10) m (quintic ramp over 10 s) about the
hang-off at x = 1600 m, 20 m below the surface, every 0.05 s for 100 s, with exact velocities and
accelerations. Columns (CableDyn): time point_id x y z vx vy vz ax ay az."""
import math

rows = ["# lazy wave heave: z = -20 + 2 r(t) sin(2 pi t/10), quintic ramp over 10 s",
        "# Columns: time(s) point_id x(m) y(m) z(m) vx vy vz ax ay az"]
w = 2 * math.pi / 10
for i in range(2001):
    t = 0.05 * i
    s = min(t / 10, 1.0)
    r = s**3 * (10 - 15 * s + 6 * s * s)
    dr = (30 * s**2 - 60 * s**3 + 30 * s**4) / 10 if t < 10 else 0.0
    ddr = (60 * s - 180 * s**2 + 120 * s**3) / 100 if t < 10 else 0.0
    z = -20.0 + 2 * r * math.sin(w * t)
    v = 2 * (dr * math.sin(w * t) + r * w * math.cos(w * t))
    a = 2 * (ddr * math.sin(w * t) + 2 * dr * w * math.cos(w * t) - r * w * w * math.sin(w * t))
    rows.append(f"{t:.2f} 1 1600.0 0.0 {z:.12e} 0.0 0.0 {v:.12e} 0.0 0.0 {a:.12e}")
open("lazy_wave_motion.txt", "w").write("\n".join(rows) + "\n")
