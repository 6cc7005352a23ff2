"""Writes rainflow-series.csv and, counted by the independent `rainflow` package
(PyPI `rainflow==3.2.0`, MIT), rainflow-cycles.csv: the vector of the test
`an_independent_counter_agrees_cycle_by_cycle` (crates/app/tests/fatigue.rs)."""
import math

import rainflow

state = 12345


def lcg():
    global state
    state = (1103515245 * state + 12345) % 2**31
    return state / 2**31


xs = []
for i in range(4000):
    t = 0.05 * i
    v = 10 * math.sin(0.7 * t) + 4 * math.sin(2.3 * t + 1.0) + 1.5 * math.sin(5.9 * t) + 3 * (lcg() - 0.5)
    v = round(v, 2)
    if i % 97 == 0 and xs:  # plateaus
        v = xs[-1]
    xs.append(v)
with open("rainflow-series.csv", "w") as f:
    f.write("# A 4000-sample test series (three sines, LCG noise, rounded to 0.01, plateaus every 97 samples).\n")
    f.write("# Counted by the independent `rainflow` 3.2.0 package (PyPI, MIT; ASTM E1049-85 three-point rule),\n")
    f.write("# rainflow.extract_cycles(series): its cycles, in the order found, are rainflow-cycles.csv.\n")
    f.write("value\n")
    for v in xs:
        f.write(f"{v:.2f}\n")
with open("rainflow-cycles.csv", "w") as f:
    f.write("# rainflow 3.2.0 extract_cycles on rainflow-series.csv: range, mean, count, in the order found.\n")
    f.write("range,mean,count\n")
    for r, m, c, _, _ in rainflow.extract_cycles(xs):
        f.write(f"{r:.17g},{m:.17g},{c}\n")
