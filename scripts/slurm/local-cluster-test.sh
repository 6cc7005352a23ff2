#!/bin/bash
# Stands up a single-node Slurm cluster on this machine (munged, slurmctld, slurmd; no cgroups, no
# accounting), runs a small catena sweep as an array of 4 tasks plus a merge job chained with
# --dependency=afterok, runs the same plan locally, and compares the two merged tables byte for byte.
# Every daemon it starts is stopped by its pid at the end. Needs root and Debian's slurm-wlm and munge
# (apt-get install slurm-wlm munge).
#   scripts/slurm/local-cluster-test.sh [path/to/catena]      (default: target/release/catena)
set -euo pipefail
repo=$(cd "$(dirname "$0")/../.." && pwd)
catena=$(realpath "${1:-$repo/target/release/catena}")
work=$(mktemp -d /tmp/catena-slurm.XXXXXX)
host=$(hostname -s)
pids=()
stop() {
  for p in "${pids[@]}"; do
    if [ -n "$p" ] && kill -0 "$p" 2>/dev/null; then kill "$p" 2>/dev/null || true; fi
  done
  sleep 1
  for p in "${pids[@]}"; do
    if [ -n "$p" ] && kill -0 "$p" 2>/dev/null; then kill -9 "$p" 2>/dev/null || true; fi
  done
}
trap stop EXIT
mkdir -p "$work"/{munge,spool,state,log,plan}
chmod 700 "$work/munge"

# munge: this machine's key (created if there is none), its own socket and pid file.
[ -f /etc/munge/munge.key ] || mungekey --create --force
munged --force --socket="$work/munge/socket" --pid-file="$work/munge/pid" \
  --log-file="$work/log/munged.log" --seed-file="$work/munge/seed"
pids+=("$(cat "$work/munge/pid")")

cpus=$(nproc)
cat > "$work/slurm.conf" <<CONF
ClusterName=catena-test
SlurmctldHost=$host
SlurmUser=root
AuthType=auth/munge
AuthInfo=socket=$work/munge/socket
CredType=cred/munge
MpiDefault=none
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/log/slurmctld.log
SlurmdLogFile=$work/log/slurmd.log
SlurmctldPort=46817
SlurmdPort=46818
NodeName=$host CPUs=$cpus State=UNKNOWN
PartitionName=debug Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$work/slurm.conf"
slurmctld -f "$SLURM_CONF"
for _ in $(seq 50); do [ -s "$work/slurmctld.pid" ] && break; sleep 0.1; done
pids+=("$(cat "$work/slurmctld.pid")")
slurmd -f "$SLURM_CONF"
for _ in $(seq 50); do [ -s "$work/slurmd.pid" ] && break; sleep 0.1; done
pids+=("$(cat "$work/slurmd.pid")")
for _ in $(seq 100); do
  sinfo -h -o %T 2>/dev/null | grep -qE '^idle' && break
  sleep 0.2
done
echo "cluster up:"; sinfo

# A small plan: the 1000 m SCR's fatigue scene, two storms of 30 s, four seabed stiffnesses.
cp "$repo/cases/scr1000/fatigue/scr1000-linear-k100.toml" "$repo/cases/scr1000/fatigue/semi-rao.csv" "$work/plan/"
printf '[[storm]]\nid = 22\nhs = 5.0\ntp = 8.4\nprobability = 0.002\n\n[[storm]]\nid = 23\nhs = 5.0\ntp = 9.9\nprobability = 0.004\n' > "$work/plan/storms.toml"
printf '[study]\nscene = "scr1000-linear-k100.toml"\nstorms = "storms.toml"\nrecord = 20.0\ntransient = 10.0\n\n[fatigue]\nsn_curve = "dnv-e-seawater-cp"\nscf = 1.2\nfibres = ["outer"]\n' > "$work/plan/study.toml"
printf '[sweep]\nbase = "study.toml"\n[[sweep.parameter]]\nkey = "seabed.stiffness"\nvalues = [50e3, 100e3, 1000e3, 10000e3]\n' > "$work/plan/plan.toml"

echo "submitting:"
CATENA="$catena" "$repo/scripts/slurm/submit.sh" "$work/plan/plan.toml" "$work/slurm-out" 4 | tee "$work/submit.txt"
merge=$(awk '{print $NF}' "$work/submit.txt")
for _ in $(seq 600); do
  state=$(scontrol show job "$merge" 2>/dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p')
  case "$state" in COMPLETED) break ;; FAILED|CANCELLED|TIMEOUT|NODE_FAIL|OUT_OF_MEMORY) echo "merge job $state"; exit 1 ;; esac
  sleep 0.5
done
echo "merge job: ${state:-unknown}"
[ "$state" = COMPLETED ] || { echo "the merge job did not complete"; exit 1; }
echo "array task logs:"; tail -n 2 "$work"/slurm-out/catena-sweep-*.out
"$catena" sweep "$work/plan/plan.toml" --out "$work/local-out" --jobs 2 --quiet > "$work/local.txt"
if cmp "$work/slurm-out/sweep.csv" "$work/local-out/sweep.csv"; then
  echo "SAME: the merged table of 4 Slurm array tasks equals the local run's, byte for byte"
  cat "$work/slurm-out/sweep.csv"
else
  echo "DIFFERENT:"; diff "$work/slurm-out/sweep.csv" "$work/local-out/sweep.csv" || true
  exit 1
fi
