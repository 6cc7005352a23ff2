#!/usr/bin/env bash
# The regression battery: runs the cases whose results.h5 a restructuring must leave identical to
# the bit (or moved by rounding, stated in the CHANGELOG), with the given catena binary, into OUT.
# Compare two batteries with scripts/compare-results.py OUT_A OUT_B (needs h5py).
# Usage: scripts/battery.sh BIN OUT   (about 2 minutes on 2 cores)
set -euo pipefail
bin=$1; out=$2
cd "$(dirname "$0")/.."
mkdir -p "$out"
run() { # name case [catena run options]
  local name=$1 case=$2; shift 2
  "$bin" run "$case" --quiet --out "$out/$name" "$@" >"$out/$name.log" 2>&1 || echo "$name: exit $?" >>"$out/failures"
}
run heave cases/benchmarks/scr-heave.toml
run watchet cases/watchet/pull-up-lay-down.toml
run watchet-no-suction cases/watchet/pull-up-lay-down-no-suction.toml
run watchet-damping cases/watchet/sensitivity/structural-damping.toml
run current cases/benchmarks/scr-current.toml
run regular-wave cases/benchmarks/scr-regular-wave.toml
for c in cases/hard/*.toml; do run "hard-$(basename "$c" .toml)" "$c"; done
run storm23 cases/scr1000/storm23.toml
run storm23-rq cases/scr1000/fatigue/scr1000-rq-fsuc0.2.toml
echo "battery in $out"
