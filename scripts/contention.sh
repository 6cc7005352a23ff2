#!/usr/bin/env bash
# One thread against two on a shared machine (issue 69; benches/README.md, "Two threads on a
# shared machine"): runs CASE with `catena run` at `--threads 1` and at the default threads,
# alternated (the order reversed every other round), beside LOADS competing busy processes (default
# 0, 1 and 2) (a shell loop each, started before the
# pair of runs and killed after), ROUNDS rounds. Prints, per run, the command's wall seconds, the
# dynamics' wall seconds (summary.json) and the steps two threads took.
#
#   scripts/contention.sh BIN CASE [ROUNDS] [LOADS] [EXTRA ARGS...]   (LOADS: e.g. "0 1 2")
#   scripts/contention.sh target/release/catena cases/scr1000/storm23.toml 2
#
# A benchmark, not a test: run it on a machine with nothing else running.
set -euo pipefail
bin=$1; case_file=$2; rounds=${3:-2}; loads=${4:-0 1 2}; shift $(( $# < 4 ? $# : 4 ))
out=$(mktemp -d)
trap 'rm -rf "$out"; kill $(jobs -p) 2>/dev/null || true' EXIT
busy=()
load() { # start $1 busy processes
  for ((i = 0; i < $1; i++)); do (while :; do :; done) & busy+=($!); done
}
unload() { for p in "${busy[@]:-}"; do [ -n "$p" ] && kill "$p" 2>/dev/null || true; done; busy=(); wait 2>/dev/null || true; }
field() { # the dynamics' wall and the steps on two threads from summary.json (a run's or a lay's)
  python3 - "$1" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
d = s.get("lay", s.get("dynamic", s))
wall = d.get("wall_seconds")
two = d.get("steps_on_two_threads")
steps = d.get("steps")
print(f"dynamics {wall:.2f} s, {two}/{steps} steps on two")
PY
}
printf '%-5s %-8s %-9s %s\n' load threads "wall (s)" summary
for ((r = 1; r <= rounds; r++)); do
  order="1 default"; [ $((r % 2)) = 0 ] && order="default 1"
  for n in $loads; do
    load "$n"
    sleep 0.5
    for threads in $order; do
      args=(); [ "$threads" = 1 ] && args=(--threads 1)
      t0=$(date +%s.%N)
      "$bin" run "$case_file" --out "$out/run" --quiet "${args[@]}" "$@" >/dev/null
      t1=$(date +%s.%N)
      printf '%-5s %-8s %-9.2f %s\n' "$n" "$threads" "$(echo "$t1 - $t0" | bc)" "$(field "$out/run/summary.json")"
    done
    unload
  done
done
