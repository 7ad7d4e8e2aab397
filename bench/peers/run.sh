#!/usr/bin/env bash
# Peer comparison: runnel's SPH step next to PySPH's `cube` benchmark at the same particle
# count, alternating, on this machine. Not part of the test suite (it installs PySPH from PyPI and
# compiles it: several minutes the first time).
#
#   bash bench/peers/run.sh [PARTICLES] [ROUNDS]      (defaults: 100000 particles, 3 rounds)
#
# Prints one JSON line per run and a summary: particle-steps/s and pair interactions per second and
# core for both. Pair interactions are nominal: particles x the neighbours a kernel's support holds
# in a lattice of spacing dx, (4/3)π(support/dx)³ — runnel: Wendland C2, support 2h = 2.4 dx (58);
# PySPH cube: cubic spline, support 2h = 3 dx (113). Each code does its own work per pair: runnel
# two neighbour passes (continuity at the drift's midpoints, then forces), PySPH WCSPH's continuity
# and momentum equations. PySPH runs with --openmp on all cores; runnel with PoCL on all cores.
set -euo pipefail
cd "$(dirname "$0")/../.."
particles=${1:-100000}
rounds=${2:-3}
venv=$(realpath -m "${PEERS_VENV:-bench/peers/.venv}")
cores=$(nproc)

bash bench/peers/install_pysph.sh "$venv"
[ -x build/runnel ] || bash scripts/build.sh

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
steps=20
pysph_run() {
  # 20 steps of dt = 1e-4 s; the first run also compiles the equations (cached in ~/.pysph), so
  # only the solver's own "Run took" time is used.
  (cd "$work" && "$venv/bin/pysph" run cube --np "$particles" --openmp --disable-output \
    --tf $(python3 -c "print($steps * 1e-4)") -d "$work/cube_output") 2>&1 |
    python3 -c '
import re, sys
text = sys.stdin.read()
n = int(re.search(r"fluid: (\d+)", text).group(1))
seconds = float(re.search(r"Run took: ([0-9.]+) secs", text).group(1))
print(n, seconds)'
}

echo "{\"machine\": \"$(grep -m1 "model name" /proc/cpuinfo | cut -d: -f2 | xargs)\", \"cores\": $cores, \"particles\": $particles}"
pysph_run > /dev/null  # compile once
python_summary=$(mktemp)
for round in $(seq 1 "$rounds"); do
  build/runnel bench sph --particles "$particles" --steps $steps 2>/dev/null | python3 -c "
import json, sys, math
d = json.load(sys.stdin)
rate = d['particle_steps_per_second']
pairs = rate * 4.0 / 3.0 * math.pi * (2.0 * d['h_factor']) ** 3 / $cores
print(json.dumps({'code': 'runnel', 'round': $round, 'particles': d['particles'], 'particle_steps_per_second': rate, 'pair_interactions_per_second_per_core': pairs}))" |
    tee -a "$python_summary"
  read -r n seconds < <(pysph_run)
  python3 -c "
import json, math
rate = $n * $steps / $seconds
pairs = rate * 4.0 / 3.0 * math.pi * 3.0 ** 3 / $cores
print(json.dumps({'code': 'pysph', 'round': $round, 'particles': $n, 'particle_steps_per_second': rate, 'pair_interactions_per_second_per_core': pairs}))" |
    tee -a "$python_summary"
done
python3 - "$python_summary" <<'PY'
import json, sys
rows = [json.loads(l) for l in open(sys.argv[1])]
for code in ("runnel", "pysph"):
    r = [x for x in rows if x["code"] == code]
    best = max(x["particle_steps_per_second"] for x in r)
    worst = min(x["particle_steps_per_second"] for x in r)
    pairs = max(x["pair_interactions_per_second_per_core"] for x in r)
    print(json.dumps({"summary": code, "particle_steps_per_second_best": best,
                      "particle_steps_per_second_worst": worst,
                      "pair_interactions_per_second_per_core_best": pairs}))
PY
rm -f "$python_summary"
