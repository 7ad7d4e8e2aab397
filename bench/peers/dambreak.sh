#!/usr/bin/env bash
# The dam break in another code: PySPH's own dam-break example, an instant release of a
# column L wide and 2L high in a 4L tank (dam_break_2d: 2-D weakly compressible SPH after
# Gomez-Gesteira et al. 2010, dx = L/33, the example's own settings), scored against Koshizuka &
# Oka (1996) by the same measure as `runnel validate dambreak`, beside runnel's run of the case.
# Not part of the test suite (it installs PySPH from PyPI; about 2 minutes after the install).
#
#   bash bench/peers/dambreak.sh [SCHEME...]     (PySPH schemes: wcsph, the default, about a minute;
#                                               edac, aha, ... about 15 minutes each at their fixed step)
#   PYSPH_DX=0.015 bash bench/peers/dambreak.sh  (PySPH at another spacing, L = 1 m; 0.015: 10 minutes)
#
# Prints one JSON line per code and scheme (mean and worst error, the front at each measured time,
# and the t* the run reached) and, per PySPH scheme, how far runnel's surge distance lies from that
# code's. A PySPH run that stops early is reported on stderr and scored on what it wrote.
set -euo pipefail
cd "$(dirname "$0")/../.."
venv=$(realpath -m "${PEERS_VENV:-bench/peers/.venv}")
schemes=("$@")
[ ${#schemes[@]} -gt 0 ] || schemes=(wcsph)

bash bench/peers/install_pysph.sh "$venv"
[ -x build/runnel ] || bash scripts/build.sh

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
reference=data/reference/dambreak_koshizuka_oka_1996.csv
score() { "$venv/bin/python" bench/peers/dambreak_front.py "$reference" "$@"; }

build/runnel validate dambreak --out "$work/runnel" > /dev/null
score runnel "$work/runnel/front.csv" runnel | tee "$work/runnel.json"
# The example's own file, with its spacing changed where it is declared: its --dx option leaves the
# particles' mass at the default spacing's.
example=$("$venv/bin/python" -c "import pysph.examples.dam_break_2d as m; print(m.__file__)")
sed "s/^dx = 0.03\$/dx = ${PYSPH_DX:-0.03}/" "$example" > "$work/dam_break_2d.py"
for scheme in "${schemes[@]}"; do
  # t* = 2.4 is t = 0.77 s for L = 1 m; an output every 50 steps (about 4 ms).
  # The run alone: the example's post-processing plots with matplotlib, which is not installed.
  (cd "$work" && "$venv/bin/python" -c "import dam_break_2d; dam_break_2d.DamBreak2D().run()" \
    --scheme "$scheme" --openmp --tf 0.8 --pfreq 50 -d "$work/$scheme" > "$work/$scheme.log" 2>&1) ||
    { echo "PySPH's dam_break_2d --scheme $scheme stopped early (scored on what it wrote):" >&2
      tail -3 "$work/$scheme.log" >&2; }
  score pysph "$work/$scheme" "pysph-$scheme" | tee "$work/$scheme.json"
  "$venv/bin/python" - "$work/runnel.json" "$work/$scheme.json" <<'PY'
import json, sys
ours, theirs = (json.load(open(p)) for p in sys.argv[1:3])
gaps = [abs((a["simulated"] - 1) - (b["simulated"] - 1)) / (b["simulated"] - 1)
        for a, b in zip(ours["front"], theirs["front"])]
print(json.dumps({"runnel_against": theirs["code"], "mean_gap": sum(gaps) / len(gaps),
                  "worst_gap": max(gaps), "points": len(gaps)}))
PY
done
