#!/bin/bash
# What splitting one run's step between two threads could give at most, on the machine at hand
# (issue 48, item 1; benches/README.md "The split step's ceiling"). Applies the probe
# benches/probes/lockstep-ceiling.patch to a temporary worktree of HEAD (a spin barrier in the
# stepper where a decomposition of the step into two halves of the line would meet, and the
# program `lockstep`), builds it and prints, round by round, the µs per step of: the full line on
# one thread; a half-size line (half the elements) on one thread; the same half-size line stepped
# on two threads at once in lockstep (meeting at each of those points and handing one thread's
# state to the other after each step: the decomposition without its halves' few shared numbers);
# and the same two threads free.
#   scripts/lockstep-ceiling.sh [heave|storm] [rounds]
# heave: the heave benchmark (400 elements, 2000 steps); storm: 400 s of the 3-hour storm's case
# (860 elements, 8000 steps). Needs what the build needs (scripts/setup.sh) and git.
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
git -C "$repo" worktree add -q --detach "$work/tree" HEAD
trap 'git -C "$repo" worktree remove --force "$work/tree"; rm -rf "$work"' EXIT
git -C "$work/tree" apply "$repo/benches/probes/lockstep-ceiling.patch"
# The repository's own target folder: the dependencies are not built again.
(cd "$work/tree" && CARGO_TARGET_DIR="$repo/target" cargo build --release -q -p catena-benches --bin lockstep)
echo "# $(nproc) processors: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//'); HEAD $(git -C "$repo" rev-parse --short HEAD)"
"$repo/target/release/lockstep" "${1:-heave}" "${2:-5}"
