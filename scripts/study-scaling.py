#!/usr/bin/env python3
"""The 30-storm study at 1 to 16 jobs (benches/README.md, "Studies by cost"): wall, CPU (the
children's user + system time), each storm's wall time from the study's own lines, and the LPT
bound (the measured storm times dealt longest first to the jobs: what no schedule of whole storms
can beat). Prints a markdown table; checks that every run's life.csv is the same bytes.

    python3 scripts/study-scaling.py NEW_CATENA [OLD_CATENA]
"""
import filecmp
import glob
import re
import resource
import subprocess
import sys
import tempfile
import time

STUDY = "cases/scr1000/fatigue/scaling/study-rq-30-storms-200s.toml"


def lpt(times, jobs):
    loads = [0.0] * jobs
    for t in sorted(times, reverse=True):
        loads[loads.index(min(loads))] += t
    return max(loads)


def main():
    bins = {"new": sys.argv[1]}
    if len(sys.argv) > 2:
        bins["old"] = sys.argv[2]
    plan = [("new", j) for j in (1, 2, 4, 8, 16)]
    if "old" in bins:
        plan += [("old", 16), ("old", 8), ("new", 16), ("new", 8), ("old", 1)]
    work = tempfile.mkdtemp()
    print("| build | jobs | wall (s) | CPU (s) | CPU / wall | storm mean (s) | storm min–max (s) "
          "| sum of storms / jobs (s) | LPT bound (s) |")
    print("|---|---|---|---|---|---|---|---|---|", flush=True)
    lives = []
    for k, (build, jobs) in enumerate(plan):
        out = f"{work}/{k}-{build}-{jobs}"
        r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.perf_counter()
        p = subprocess.run([bins[build], "fatigue", STUDY, "--out", out, "--jobs", str(jobs)],
                           capture_output=True, text=True, check=True)
        wall = time.perf_counter() - t0
        r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = r1.ru_utime - r0.ru_utime + r1.ru_stime - r0.ru_stime
        storms = [float(x) for x in re.findall(r"\): ([0-9.]+) s;", p.stdout + p.stderr)]
        print(f"| {build} | {jobs} | {wall:.2f} | {cpu:.1f} | {cpu / wall:.2f} "
              f"| {sum(storms) / len(storms):.2f} | {min(storms):.1f}–{max(storms):.1f} "
              f"| {sum(storms) / jobs:.1f} | {lpt(storms, jobs):.1f} |", flush=True)
        lives.append(f"{out}/life.csv")
    same = all(filecmp.cmp(lives[0], f, shallow=False) for f in lives)
    print(f"\nlife.csv identical in all {len(lives)} runs: {same}")
    sys.exit(0 if same else 1)


if __name__ == "__main__":
    main()
