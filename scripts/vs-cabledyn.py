#!/usr/bin/env python3
"""The heave benchmark side by side with CableDyn 0.3.0, the same hour (issue 69, item 2;
benches/README.md, "Side by side, the same hour").

Each round runs CableDyn on its deck of the benchmark (`validation/cabledyn/scr-heave.dat`, its
motion file written by `validation/cabledyn/heave_motion.py`) `--cabledyn-runs` times, then
catena's whole command as a user runs it (`catena run cases/benchmarks/scr-heave.toml --out DIR
--quiet`: statics, 2000 steps, `results.h5`, `summary.json`, three plots) `--catena-runs` times,
alternating the two programs round by round so that both see the same host. It prints, per round,
CableDyn's mean (range), catena's median (fastest) and the ratio of the two, then a Markdown table
to paste into benches/README.md. With `--storm` each round also times the 3-hour storm
(`cases/scr1000/storm23-3h.toml`, its outputs, the default threads) once: the issue's other target.

CableDyn is not a dependency: without `--cabledyn` it is installed from PyPI into a throwaway
virtual environment (`--venv`, default `target/cabledyn-venv`) the first time.

    python3 scripts/vs-cabledyn.py                      # 2 rounds, target/release/catena
    python3 scripts/vs-cabledyn.py --rounds 3 --storm   # and the 3-hour storm once a round

A benchmark, not a test: run it with nothing else on the machine (the ratio moves with the host:
CableDyn gains more from a quick one than catena does, benches/README.md).
"""

import argparse
import glob
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DECKS = os.path.join(ROOT, "validation", "cabledyn")


def cabledyn_binary(venv):
    """The CableDyn program in `venv`, installed there first if it is not."""
    pattern = os.path.join(venv, "lib", "python3*", "site-packages", "cabledyn", "bin", "cabledyn")
    found = glob.glob(pattern)
    if not found:
        print(f"installing CableDyn 0.3.0 into {venv}", file=sys.stderr)
        subprocess.run([sys.executable, "-m", "venv", venv], check=True)
        pip = os.path.join(venv, "bin", "pip")
        subprocess.run([pip, "install", "-q", "cabledyn==0.3.0"], check=True)
        found = glob.glob(pattern)
    if not found:
        sys.exit(f"vs-cabledyn: no CableDyn program at {pattern} after installing it")
    return found[0]


def wall(cmd, cwd=None):
    """Seconds one run of `cmd` took; a failed run stops the script with its output."""
    start = time.perf_counter()
    done = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True)
    seconds = time.perf_counter() - start
    if done.returncode != 0:
        sys.exit(f"vs-cabledyn: {' '.join(cmd)} failed ({done.returncode}):\n{done.stderr[-2000:]}")
    return seconds


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--catena", default=os.path.join(ROOT, "target", "release", "catena"))
    ap.add_argument("--cabledyn", help="CableDyn's program (default: from --venv)")
    ap.add_argument("--venv", default=os.path.join(ROOT, "target", "cabledyn-venv"))
    ap.add_argument("--rounds", type=int, default=2)
    ap.add_argument("--cabledyn-runs", type=int, default=3)
    ap.add_argument("--catena-runs", type=int, default=21)
    ap.add_argument("--storm", action="store_true", help="time the 3-hour storm once a round")
    args = ap.parse_args()
    if not os.path.exists(args.catena):
        sys.exit(f"vs-cabledyn: no catena program at {args.catena} (cargo build --release)")
    cabledyn = args.cabledyn or cabledyn_binary(args.venv)

    work = tempfile.mkdtemp(prefix="vs-cabledyn-")
    try:
        shutil.copy(os.path.join(DECKS, "scr-heave.dat"), work)
        subprocess.run([sys.executable, os.path.join(DECKS, "heave_motion.py")], cwd=work, check=True)
        heave = os.path.join(ROOT, "cases", "benchmarks", "scr-heave.toml")
        storm = os.path.join(ROOT, "cases", "scr1000", "storm23-3h.toml")
        out = os.path.join(work, "catena")
        # CableDyn writes its outputs beside the root it is given.
        cd_cmd = [cabledyn, "scr-heave.dat", os.path.join(work, "cd")]
        ca_cmd = [args.catena, "run", heave, "--out", out, "--quiet"]
        rows = []
        for r in range(1, args.rounds + 1):
            stamp = time.strftime("%H:%M")
            cd = [wall(cd_cmd, cwd=work) for _ in range(args.cabledyn_runs)]
            ca = [wall(ca_cmd) for _ in range(args.catena_runs)]
            m, c = statistics.mean(cd), statistics.median(ca)
            st = wall([args.catena, "run", storm, "--out", out, "--quiet"]) if args.storm else None
            rows.append((r, stamp, m, min(cd), max(cd), c, min(ca), m / c, st))
            line = (f"round {r} ({stamp}): CableDyn {m:.2f} s ({min(cd):.2f}–{max(cd):.2f}), "
                    f"catena {c * 1e3:.1f} ms (fastest {min(ca) * 1e3:.1f}): {m / c:.1f}×")
            if st is not None:
                line += f"; the 3-hour storm {st:.2f} s"
            print(line, flush=True)
        print()
        head = "| round | CableDyn (mean, range) | catena (median; fastest) | ratio |"
        rule = "|---|---|---|---|"
        if args.storm:
            head, rule = head + " 3-hour storm |", rule + "---|"
        print(head)
        print(rule)
        for r, stamp, m, lo, hi, c, fast, ratio, st in rows:
            cells = (f"| {r} ({stamp}) | {m:.2f} s ({lo:.2f}–{hi:.2f}) | "
                     f"{c * 1e3:.1f} ms ({fast * 1e3:.1f}) | **{ratio:.1f}×** |")
            if st is not None:
                cells += f" {st:.2f} s |"
            print(cells)
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
