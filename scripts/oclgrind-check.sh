#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# runnel's kernels on a second OpenCL implementation: Oclgrind, a simulated device that checks every
# memory access and, with data-race detection, every pair of work-items touching one address with
# no barrier or atomic between them. PoCL runs a work-group's items one after another on one thread,
# so a missing barrier or an access past a buffer's end can pass unseen there and fail on a GPU.
# Oclgrind calls itself a GPU: the runs below take a GPU's cut (a work-item per particle, the sort
# in tiles), and the benchmark with --tile 32 the CPU's tiled neighbour passes (local memory,
# barriers, the tank walls' images). docs/robustness.md, "Kernels on a second OpenCL implementation".
#
# Usage: scripts/oclgrind-check.sh [--tests FILTER] [--timeout SECONDS] [--jobs N] [--build DIR]
#   with no option: a short run of each model and of the SPH benchmark's tiles (3-4 minutes);
#   --tests FILTER: also the tests of runnel_tests that match the gtest filter, each in a process
#   of its own (RUNNEL_TEST_DEVICE=Oclgrind; '*' takes hours: Oclgrind interprets every
#   work-item), at most SECONDS each (default 600), N at a time (default 1).
# Fails when a run or test fails or times out, or when Oclgrind reports anything. Exit 77 (CTest's
# skip) when Oclgrind is not installed.
set -euo pipefail
cd "$(dirname "$0")/.."

filter=""
timeout_s=600
jobs=1
build=build
while [[ $# -gt 0 ]]; do
  case "$1" in
    --tests) filter="$2"; shift 2 ;;
    --timeout) timeout_s="$2"; shift 2 ;;
    --jobs) jobs="$2"; shift 2 ;;
    --build) build="$2"; shift 2 ;;
    *) echo "oclgrind-check: unknown argument '$1' (see the script's header)" >&2; exit 2 ;;
  esac
done

icd_library=/usr/lib/oclgrind/liboclgrind-rt-icd.so
if [[ ! -f "$icd_library" ]]; then
  echo "oclgrind-check: skipped: Oclgrind is not installed (no $icd_library; scripts/setup.sh installs it)"
  exit 77
fi
for binary in "$build/runnel" "$build/tests/runnel_tests"; do
  if [[ ! -x "$binary" ]]; then
    echo "oclgrind-check: $binary: not built (bash scripts/build.sh)" >&2
    exit 2
  fi
done

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# Oclgrind as the only OpenCL platform of these processes, without registering it system-wide.
echo "$icd_library" >"$work/oclgrind.icd"
export OCL_ICD_VENDORS="$work/oclgrind.icd"
export OCLGRIND_DATA_RACES=1 OCLGRIND_MAX_ERRORS=20
export OCLGRIND_GLOBAL_MEM_SIZE=2147483648  # 2 GiB: its default, 128 MiB, is less than some tests take
export RUNNEL_DEVICE=Oclgrind RUNNEL_TEST_DEVICE=Oclgrind
export timeout_s work

# check NAME COMMAND...: runs one command, its output kept; one line of verdict.
check() {
  local name="$1" log start=$SECONDS rc=0
  shift
  log="$work/$(echo "$name" | tr '/ ' '__').log"
  timeout "$timeout_s" "$@" >"$log" 2>&1 || rc=$?
  local verdict=ok
  # Oclgrind's reports: an access outside a buffer, a data race, a divergent barrier, an API error.
  if grep -q -E '^(Invalid (read|write)|.*data race|Work-group divergence|Work-item divergence|Oclgrind - OpenCL runtime error)' "$log"; then
    verdict="Oclgrind reported"
  elif [[ $rc -eq 124 ]]; then
    verdict="timed out after $timeout_s s"
  elif [[ $rc -ne 0 ]]; then
    verdict="failed (exit $rc)"
  fi
  echo "$verdict|$((SECONDS - start))|$name" >>"$work/verdicts"
  printf '  %-9s %4d s  %s\n' "${verdict%% *}" "$((SECONDS - start))" "$name"
  if [[ "$verdict" != ok ]]; then
    grep -v -E '^\[ *(RUN|OK) ' "$log" | head -40 | sed 's/^/    /' || true  # (an empty log: no lines)
  fi
  return 0
}
export -f check

runnel="$build/runnel"
scenario=data/scenarios/default.toml
echo "oclgrind-check: runnel's kernels on Oclgrind, with data-race detection"
# SPH rain erosion, a GPU's cut: rain, contact, the water depth, the bed exchange, the sort in tiles.
check "sph run" "$runnel" run "$scenario" --quiet --out "$work/sph" --set terrain.size=17 \
  --set rain.intensity=1000000 --sim-time 0.8
# The same with the incompressible solver (its density pass, neighbour lists and pressure solves),
# and its solves in a tank (wall ghosts, water under pressure).
check "sph run, dfsph" "$runnel" run "$scenario" --quiet --out "$work/sph_dfsph" --set terrain.size=17 \
  --set rain.intensity=1000000 --set sph.solver=dfsph --sim-time 0.8
check "sph bench, dfsph" "$runnel" bench sph --particles 250 --steps 1 --set sph.solver=dfsph
# The CPU's tiled neighbour passes (one work-group a tile, candidates in local memory) in a tank.
check "sph bench, tiles of 32" "$runnel" bench sph --particles 1000 --steps 2 --tile 32
# The comparison models, and the noise generators that run on a device.
# (Hills steep enough for the talus to slide.)
check "compare droplet,pipe,olsen,thermal" "$runnel" compare "$scenario" --quiet --out "$work/compare" \
  --models droplet,pipe,olsen,thermal --set terrain.size=33 --set terrain.set.relief=0.6 \
  --set run.sim_time=2
for generator in value-noise turbulence; do
  check "generate $generator" "$runnel" generate "$generator" --device Oclgrind --size 129 \
    -o "$work/$generator.npy"
done

if [[ -n "$filter" ]]; then
  "$build/tests/runnel_tests" --gtest_list_tests --gtest_filter="$filter" |
    awk '/^[^ ]/ { suite = $1 } /^  / { print suite $1 }' >"$work/tests"
  echo "oclgrind-check: $(wc -l <"$work/tests") tests of runnel_tests ($jobs at a time)"
  export tests_binary="$build/tests/runnel_tests"
  xargs -P "$jobs" -I{} bash -c 'check "$1" "$tests_binary" --gtest_filter="$1"' _ {} <"$work/tests"
fi

total=$(wc -l <"$work/verdicts")
bad=$(grep -c -v '^ok|' "$work/verdicts" || true)
echo "oclgrind-check: $((total - bad)) of $total clean"
[[ "$bad" -eq 0 ]]
