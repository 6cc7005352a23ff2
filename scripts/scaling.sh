#!/bin/bash
# Cost against problem size: the heave benchmark's riser meshed with 100 to 3200 elements, 400 steps
# of 0.05 s each (20 s, records every 5 s), one core. Prints elements, steps, wall time of the
# dynamics, and µs per element-step (benches/README.md "Scaling").
#   scripts/scaling.sh [path/to/catena]
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
catena=${1:-$repo/target/release/catena}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
printf "| elements | steps | dynamics wall (s) | µs per element-step | Newton iterations per step |\n|---|---|---|---|---|\n"
for n in 100 200 400 800 1600 3200; do
  len=$(python3 -c "print(1600.0/$n)")
  sed -e "s/^element_length = 4.0/element_length = $len/" -e 's/^duration = 100.0 .*/duration = 20.0/' \
      -e 's/^envelope_start = 50.0 .*/envelope_start = 10.0\noutput_interval = 5.0/' \
      "$repo/cases/benchmarks/scr-heave.toml" > "$work/s$n.toml"
  "$catena" run "$work/s$n.toml" --out "$work/o$n" > /dev/null
  python3 - "$work/o$n/summary.json" "$n" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))["dynamic"]
n = int(sys.argv[2])
w = d["wall_seconds"]
print(f"| {n} | {d['steps']} | {w:.3f} | {w * 1e6 / (n * d['steps']):.3f} | {d['iterations_per_step']:.2f} |")
PY
done
