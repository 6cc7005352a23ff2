#!/usr/bin/env bash
# The dynamic lay study of validation/lay.md: the 12-inch J-lay (cases/lay/jlay-12in-hs2.toml) laying
# 200 m in Hs 0 (calm), 0.5, 1, 2 and 3 m on the paper's law (λrep 0.3), with cyclic degradation, and
# with λrep 0.1 and 0.6; and at Hs 2 m at half and twice the lay rate. One line per run in
# validation/lay/def-vs-hs.csv (the as-laid embedment, the dynamic embedment factor over the
# self-weight and over the static embedment with force concentration, the lay factor, episodes and
# wall time). About 4 minutes on 2 cores.
# Usage: scripts/lay-study.sh [CATENA_BINARY]
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-target/release/catena}
work=$(mktemp -d)
cp cases/lay/lay-vessel-rao.csv "$work/"
out=validation/lay/def-vs-hs.csv
echo "variant,hs_m,speed_m_per_s,as_laid_mean_mm,as_laid_min_mm,as_laid_max_mm,self_weight_mm,static_fc_mm,def_self_weight,def_static_fc,lay_factor,static_lay_factor,episodes_mean,steady_nodes,wall_s" >"$out"
run() { # variant hs speed edit-script
  local variant=$1 hs=$2 speed=$3 script=$4
  local case="$work/$variant-$hs-$speed.toml"
  python3 - "$hs" "$speed" "$script" >"$case" <<'PY'
import sys
hs, speed, script = float(sys.argv[1]), float(sys.argv[2]), sys.argv[3]
s = open("cases/lay/jlay-12in-hs2.toml").read()
s = s.replace("length = 500.0                # m of pipe laid [A]", "length = 200.0")
s = s.replace("speed = 0.025                 # m/s [A] (2.2 km/day, a J-lay rate)", f"speed = {speed}")
s = s.replace("duration = 20100.0            # s (the lay ends at 500 m, at 20 000 s)", f"duration = {200.0 / speed + 100.0}")
if hs == 0.0:
    a = s.index("[waves]"); b = s.index("[lay]")
    s = s[:a] + s[b:]
else:
    s = s.replace("hs = 2.0                      # m [A]", f"hs = {hs}")
if script == "degradation":
    s = s.replace("[hydrodynamics]", "[seabed.degradation]\nsensitivity = 3.0\nductility = 25.0\n\n[hydrodynamics]", 1)
elif script.startswith("lambda_rep="):
    s = s.replace("lambda_rep = 0.3", "lambda_rep = " + script.split("=")[1])
print(s)
PY
  "$bin" run "$case" --quiet --out "$work/out" >/dev/null
  python3 - "$variant" "$hs" "$speed" "$work/out/summary.json" >>"$out" <<'PY'
import json, sys
variant, hs, speed, path = sys.argv[1:]
l = json.load(open(path))["lay"]
e = l["as_laid_embedment"]
mm = lambda v: f"{1e3 * v:.2f}" if v is not None else ""
print(",".join([variant, hs, speed, mm(e["mean"]), mm(e["min"]), mm(e["max"]), mm(l["self_weight_embedment"]),
                mm(l["static_embedment"]), f'{e["mean"] / l["self_weight_embedment"]:.3f}',
                f'{e["mean"] / l["static_embedment"]:.3f}', f'{l["lay_factor"]:.3f}', f'{l["static_lay_factor"]:.3f}',
                f'{l["episodes_mean"]:.2f}', str(l["steady_nodes"]), f'{l["wall_seconds"]:.1f}']))
PY
  tail -1 "$out"
}
for hs in 0.0 0.5 1.0 2.0 3.0; do
  run paper "$hs" 0.025 none
  run degradation "$hs" 0.025 degradation
  run lambda_rep_0.1 "$hs" 0.025 lambda_rep=0.1
  run lambda_rep_0.6 "$hs" 0.025 lambda_rep=0.6
done
run paper-half-rate 2.0 0.0125 none
run paper-twice-rate 2.0 0.05 none
rm -rf "$work"
echo "wrote $out"
