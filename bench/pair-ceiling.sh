#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# How fast the SPH benchmark could be with fewer candidates in its pair loop: builds
# throwaway copies of this tree whose two tiled neighbour passes evaluate only the first N
# candidates of each tile's list (their results are wrong: timing only), everything else unchanged,
# and runs `runnel bench sph` on each, alternating. N = all is the tree as it is; 200 stands for
# rows sorted along x (about half the candidates), 64 for a perfect neighbour filter (~58
# neighbours padded to the vector width), 0 for the passes' walks, copies and boundary terms and the
# rest of the step alone. Not part of the test suite; docs/performance.md, "What limits `wcsph`,
# measured", gives its figures.
#
#   bash bench/pair-ceiling.sh [PARTICLES] [ROUNDS] [CAPS]   (defaults: 100000, 2, "all 200 64 0")
#
# Prints one JSON line per run (cap, particle-steps/s, the two tiled passes' seconds) and a summary.
# The copies are built in a temporary directory (the first build takes minutes; each further cap
# rebuilds only the embedded kernels) and removed at the end; the tree itself is not touched.
set -euo pipefail
cd "$(dirname "$0")/.."
particles=${1:-100000}
rounds=${2:-2}
caps=${3:-all 200 64 0}

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# The pair loop of each tiled pass, as the kernels spell it; the script refuses to run if either file
# no longer has exactly one, rather than time an unpatched pass.
passes=(cl/sph_forces.cl cl/sph_continuity.cl)
loop='      for (uint k = 0; k < length; ++k) {'
for f in "${passes[@]}"; do
  if [ "$(grep -c -F -x "$loop" "$f")" != 1 ]; then
    echo "pair-ceiling: $f: expected one pair loop '$loop'" >&2
    exit 2
  fi
done

# The tree's tracked files as they are in the working tree (uncommitted changes included).
git ls-files -z | xargs -0 cp --parents -t "$work"
python_args=()
if [ -x /usr/bin/python3 ]; then python_args+=(-DPython3_EXECUTABLE=/usr/bin/python3); fi
binaries="$work/binaries"
mkdir -p "$binaries"
for cap in $caps; do
  for f in "${passes[@]}"; do
    cp "$f" "$work/$f"
    if [ "$cap" != all ]; then
      sed -i "s|^$loop\$|      for (uint k = 0; k < (base == 0 ? min(length, ${cap}u) : 0u); ++k) {|" "$work/$f"
    fi
  done
  echo "pair-ceiling: building the copy with the pair loop over $cap candidates" >&2
  (cd "$work" && cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "${python_args[@]}" >/dev/null &&
    cmake --build build -j "$(nproc)" --target runnel >/dev/null)
  cp "$work/build/runnel" "$binaries/runnel-$cap"
done

results="$work/results.jsonl"
for round in $(seq "$rounds"); do
  for cap in $caps; do
    "$binaries/runnel-$cap" bench sph --particles "$particles" --steps 20 |
      python3 -c '
import json, sys
d = json.load(sys.stdin)
k = d["kernel_seconds"]
print(json.dumps({"cap": sys.argv[1], "round": int(sys.argv[2]), "device": d["device"],
                  "particles": d["particles"],
                  "particle_steps_per_second": round(d["particle_steps_per_second"]),
                  "sph_forces_s": round(k.get("sph_forces", 0.0), 4),
                  "sph_continuity_s": round(k.get("sph_continuity", 0.0), 4)}))' "$cap" "$round" |
      tee -a "$results"
  done
done
python3 - "$results" <<'EOF'
import json, sys
runs = [json.loads(line) for line in open(sys.argv[1])]
for cap in dict.fromkeys(r["cap"] for r in runs):
    rates = [r["particle_steps_per_second"] / 1e6 for r in runs if r["cap"] == cap]
    print(f"pair loop over {cap:>3} candidates: {min(rates):.2f}-{max(rates):.2f} M particle-steps/s")
EOF
