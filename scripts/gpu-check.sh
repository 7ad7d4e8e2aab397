#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# One prepared run on a machine with a GPU (issue 15): builds runnel, lists the OpenCL devices, runs
# `runnel bench sph` at 1 M and 4 M particles, the grid benchmarks at 4096² and the noise generators at
# 4097² on the GPU, the test
# suite with its OpenCL tests on the GPU, and reports the viewer's frame rate where a display is
# there; each step under its own time limit so the whole fits in 8 minutes. Writes
# ${OUT:-gpu-check-out}/gpu-check.json (one object: each step's JSON, or why it did not run).
#   DEVICE=gpu        the device to measure (see `runnel devices`)
#   SCALE=1           1: the sizes above; e.g. SCALE=0.01 for a dry run on a CPU
set -uo pipefail
cd "$(dirname "$0")/.."
out="${OUT:-gpu-check-out}"
device="${DEVICE:-gpu}"
scale="${SCALE:-1}"
mkdir -p "$out"
summary="$out/gpu-check.json"
log="$out/gpu-check.log"
: >"$log"
entries=()

# Runs a step under a time limit; its stdout (JSON) becomes the entry, else the reason it failed.
step() {
  local name="$1" limit="$2"
  shift 2
  local start end output rc
  start=$(date +%s.%N)
  output=$(timeout "$limit" "$@" 2>>"$log")
  rc=$?
  end=$(date +%s.%N)
  local seconds
  seconds=$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.3f", b - a }')
  if [ $rc -eq 0 ] && [ -n "$output" ]; then
    entries+=("\"$name\": {\"seconds\": $seconds, \"result\": $output}")
  else
    local why="exit $rc"
    [ $rc -eq 124 ] && why="timed out after $limit s"
    entries+=("\"$name\": {\"seconds\": $seconds, \"failed\": \"$why (see gpu-check.log)\"}")
  fi
  echo "gpu-check: $name: rc $rc, $seconds s" >&2
}
scaled() { awk -v n="$1" -v s="$scale" 'BEGIN { v = int(n * s); if (v < 1) v = 1; print v }'; }

# 1. Build (no package installation: the machine may have no network; missing tools are reported; it
# needs the packages of scripts/setup.sh, KissFFT among them).
if ! command -v cmake >/dev/null; then
  echo '{"failed": "cmake is not installed on this machine"}' >"$summary"
  exit 1
fi
# scripts/build.sh: the same configuration as the README's commands (the Python tests in the
# package's virtual environment), into build-gpu/ with the viewer.
step build 240 bash -c 'RUNNEL_BUILD_DIR=build-gpu RUNNEL_CMAKE_ARGS=-DRUNNEL_BUILD_VIEWER=ON bash scripts/build.sh >&2 &&
  echo "{\"ok\": true}"'
runnel=build-gpu/runnel

# 2. Devices.
step devices 30 bash -c "$runnel devices --json 2>/dev/null || $runnel devices | python3 -c 'import json,sys; print(json.dumps(sys.stdin.read()))'"

# 3. SPH at 1 M and 4 M particles.
for n in 1000000 4000000; do
  step "sph_$n" 120 "$runnel" bench sph --particles "$(scaled $n)" --steps 20 --device "$device"
done

# 4. Grid models at 4096².
size=$(scaled 4096)
[ "$size" -lt 64 ] && size=64
for model in pipe olsen thermal droplet; do
  step "${model}_${size}" 60 "$runnel" bench "$model" --size "$size" --steps 10 --device "$device"
done

# 4b. The noise generators at 4097² (issue 19): the same bytes as on the CPU, vertices per second.
gsize=$(scaled 4097)
[ "$gsize" -lt 64 ] && gsize=64
step "generate_${gsize}" 60 "$runnel" bench generate --size "$gsize" --steps 2 --device "$device"

# 5. The test suite, its OpenCL tests on the GPU (the CLI picks the first GPU by itself). The Python
# package's tests need its virtual environment (scripts/setup-python.sh, from PyPI): without one
# they are left out, and the log says so.
skip_python=()
if [ ! -x .venv/bin/python ]; then
  skip_python=(-E '^Python\.')
  echo "gpu-check: tests: no .venv (scripts/setup-python.sh), the Python package's tests left out" >>"$log"
fi
step tests 180 bash -c "cd build-gpu && RUNNEL_TEST_DEVICE=$device ctest -j \"\$(nproc)\" -LE fuzz ${skip_python[*]} >&2 &&
  echo '{\"all_passed\": true}'"

# 6. The viewer at 1280x800 (issue 21): with the GPU's own OpenGL when there is a display; otherwise
# under Xvfb, where the simulation runs on the GPU's OpenCL but the drawing is Mesa's software
# rasteriser (the entry says which). 20,000 particles from a short run of the default scenario.
viewer_fps() {
  "$runnel" run data/scenarios/default.toml --set rain.rate=10000 --set rain.max_particles=20000 \
    --sim-time 2.5 --device "$device" --out "$out/p20k" >/dev/null 2>&1 || return 1
  local running paused  # the last stats line of each: frames/s simulating, and drawing only
  running=$(build-gpu/runnel-viewer "$out/p20k/final.h5" --device "$device" --size 1280x800 \
    --frames 120 --stats-every 60 2>/dev/null | tail -1)
  paused=$(build-gpu/runnel-viewer "$out/p20k/final.h5" --device "$device" --size 1280x800 \
    --frames 120 --stats-every 60 --paused 2>/dev/null | tail -1)
  [ -n "$running" ] && [ -n "$paused" ] && echo "{\"simulating\": $running, \"paused\": $paused}"
}
if [ -n "${DISPLAY:-}" ]; then
  step viewer_gpu_gl 150 bash -c "$(declare -f viewer_fps); runnel=$runnel device=$device out=$out viewer_fps"
elif command -v Xvfb >/dev/null; then
  step viewer_xvfb_software_gl 150 bash -c "Xvfb :97 -screen 0 1280x900x24 -nolisten tcp >/dev/null 2>&1 & x=\$!;
    until DISPLAY=:97 xdpyinfo >/dev/null 2>&1; do sleep 0.2; done; export DISPLAY=:97; $(declare -f viewer_fps); runnel=$runnel device=$device out=$out viewer_fps; kill \$x"
else
  entries+=("\"viewer\": {\"skipped\": \"no display and no Xvfb on this machine\"}")
fi

{
  echo "{"
  echo "  \"device\": \"$device\", \"scale\": $scale, \"date\": \"$(date -u +%FT%TZ)\","
  for k in "${!entries[@]}"; do
    sep=","
    [ "$k" -eq $((${#entries[@]} - 1)) ] && sep=""
    echo "  ${entries[$k]}$sep"
  done
  echo "}"
} >"$summary"
echo "gpu-check: wrote $summary" >&2
