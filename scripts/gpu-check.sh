#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# One prepared run on a machine with a GPU: lists the OpenCL devices, runs `runnel bench
# sph` at 1 M, 4 M, 16 M (and 100 k) particles, the grid benchmarks at 4096² and the noise generators at 4097², a
# 30-s and a whole default run, the test suite with its OpenCL tests on the GPU, and the viewer's
# painting loop drawn headless through EGL. Each step has its own time limit and the whole run a budget
# (the steps are in order of importance; one that no longer fits is skipped and says so).
# Writes ${OUT:-gpu-check-out}/gpu-check.json after every step (one object: each step's JSON, or why
# it did not run), the log beside it, and the test suite's output in tests.log.
#
# runnel comes from .gpu/bundle.tar.xz when there is one (scripts/gpu-bundle.sh, made on a Debian
# machine: the GPU machine may have no network and none of the -dev packages), else it is built.
#   DEVICE=gpu           the device to measure (see `runnel devices`)
#   SCALE=1              1: the sizes above; e.g. SCALE=0.002 for a dry run on a CPU
#   GPU_CHECK_SECONDS    the whole run's budget (default 480)
#   GPU_CHECK_SKIP       steps to leave out, by the first word of their names ("pipe olsen tests")
#   GPU_CHECK_TESTS      only the tests whose names match this regular expression (ctest -R)
set -uo pipefail
cd "$(dirname "$0")/.."
out="${OUT:-gpu-check-out}"
device="${DEVICE:-gpu}"
scale="${SCALE:-1}"
deadline=$(($(date +%s) + ${GPU_CHECK_SECONDS:-480}))
mkdir -p "$out"
out=$(cd "$out" && pwd)
summary="$out/gpu-check.json"
log="$out/gpu-check.log"
: >"$log"
entries=()

write_summary() {
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
}

# Runs a step under a time limit (cut to what is left of the budget); its stdout (JSON) becomes the
# entry, else the reason it failed.
step() {
  local name="$1" limit="$2"
  shift 2
  local left=$((deadline - $(date +%s)))
  if [[ " ${GPU_CHECK_SKIP:-} " == *" ${name%%_*} "* ]]; then
    entries+=("\"$name\": {\"skipped\": \"left out (GPU_CHECK_SKIP)\"}")
    write_summary
    return
  fi
  if [ "$left" -lt 15 ]; then
    entries+=("\"$name\": {\"skipped\": \"the run's budget was spent\"}")
    echo "gpu-check: $name: skipped, out of time" >&2
    write_summary
    return
  fi
  [ "$limit" -gt "$left" ] && limit=$left
  local start end output rc seconds
  echo "== $name (limit $limit s)" >>"$log"
  start=$(date +%s.%N)
  output=$(timeout "$limit" "$@" 2>>"$log")
  rc=$?
  end=$(date +%s.%N)
  seconds=$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.3f", b - a }')
  if [ $rc -eq 0 ] && [ -n "$output" ]; then
    entries+=("\"$name\": {\"seconds\": $seconds, \"result\": $output}")
  else
    local why="exit $rc"
    [ $rc -eq 124 ] && why="timed out after $limit s"
    entries+=("\"$name\": {\"seconds\": $seconds, \"failed\": \"$why (see gpu-check.log)\"}")
  fi
  echo "gpu-check: $name: rc $rc, $seconds s" >&2
  write_summary
}
scaled() { awk -v n="$1" -v s="$scale" 'BEGIN { v = int(n * s); if (v < 1) v = 1; print v }'; }

# The machine, for the record.
{
  echo "== machine"
  grep -E '^(PRETTY_NAME)=' /etc/os-release 2>/dev/null
  ldd --version 2>&1 | head -1
  nproc
  command -v nvidia-smi >/dev/null &&
    nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.sm,clocks.max.sm --format=csv
} >>"$log" 2>&1

# The NVIDIA OpenCL driver, for an ICD loader that has no vendor file for it (containers often
# mount the driver's libraries without one in /etc/OpenCL/vendors): the machine's vendor files
# and one for NVIDIA's library, in a folder of our own.
icd=$(find /usr/local/nvidia /usr/lib/x86_64-linux-gnu /usr/lib64 /usr/lib /lib /opt -maxdepth 4 \
  -name 'libnvidia-opencl.so*' 2>/dev/null | sort | head -1)
echo "gpu-check: NVIDIA's OpenCL library: ${icd:-not found}; vendor files: $(cat /etc/OpenCL/vendors/*.icd 2>/dev/null | tr '\n' ' ')" >>"$log"
[ -n "$icd" ] || ls /usr/local/nvidia/lib64 /usr/local/nvidia/lib 2>/dev/null | tr '\n' ' ' >>"$log"
if [ -n "$icd" ] && ! grep -qs nvidia /etc/OpenCL/vendors/*.icd; then
  mkdir -p /tmp/runnel-icd
  cp /etc/OpenCL/vendors/*.icd /tmp/runnel-icd/ 2>/dev/null
  echo "$icd" >/tmp/runnel-icd/nvidia.icd
  export OCL_ICD_VENDORS=/tmp/runnel-icd
fi

# 1. runnel: unpacked from the bundle, else built (needs the packages of scripts/setup.sh).
if [ -f .gpu/bundle.tar.xz ]; then
  # The binaries look for data/ and for each other in the tree they were built in.
  step unpack 60 bash -c 'tar -xJf .gpu/bundle.tar.xz && built_in=$(cat .gpu/built-in) &&
    { [ -e "$built_in" ] || { mkdir -p "$(dirname "$built_in")" && ln -s "$PWD" "$built_in"; }; } &&
    { [ "$built_in" -ef . ] || echo "gpu-check: the tests read $built_in, not this tree" >&2; } &&
    ! ldd build/runnel | grep -i "not found" >&2 &&
    build/runnel --version >&2 && echo "{\"ok\": true}"'
  build=build
elif command -v cmake >/dev/null; then
  # scripts/build.sh: the same configuration as the README's commands, into build-gpu/ with the viewer.
  step build 240 bash -c 'RUNNEL_BUILD_DIR=build-gpu RUNNEL_CMAKE_ARGS=-DRUNNEL_BUILD_VIEWER=ON bash scripts/build.sh >&2 &&
    echo "{\"ok\": true}"'
  build=build-gpu
else
  entries+=("\"build\": {\"failed\": \"no .gpu/bundle.tar.xz and no cmake on this machine\"}")
  write_summary
  exit 1
fi
runnel=$build/runnel

# 2. Devices.
step devices 30 "$runnel" devices --json

# 3. SPH at 1 M, 4 M and 16 M particles, and at the 100 k of the CPU figures; then at 4 M with the
# CPU's tiles (a work-group of a cell's particles sharing candidates in local memory) beside the
# GPU's own passes (a work-item a particle).
for n in 1000000 4000000 16000000 100000; do
  step "sph_$n" 120 "$runnel" bench sph --particles "$(scaled $n)" --steps 20 --device "$device"
done
step sph_4000000_tile32 120 "$runnel" bench sph --particles "$(scaled 4000000)" --steps 20 --tile 32 \
  --device "$device"
# The incompressible solver on the same block (its simulated seconds per wall second beside wcsph's).
step sph_1000000_dfsph 120 "$runnel" bench sph --particles "$(scaled 1000000)" --steps 20 --device "$device" \
  --set sph.solver=dfsph
# Both solvers on a film two particles deep running down a slope, the shape of a storm's water, and
# on the block dropped onto the floor (falling and landing).
for scene in sheet fall; do
  for solver in wcsph dfsph; do
    step "sph_${scene}_1000000_$solver" 120 "$runnel" bench sph --scene "$scene" \
      --particles "$(scaled 1000000)" --steps 20 --device "$device" --set sph.solver=$solver
  done
done

# 4. Grid models at 4096².
size=$(scaled 4096)
[ "$size" -lt 64 ] && size=64
for model in pipe olsen thermal droplet; do
  step "${model}_${size}" 60 "$runnel" bench "$model" --size "$size" --steps 10 --device "$device"
done

# 4b. The noise generators at 4097²: the same bytes as on the CPU, vertices per second.
gsize=$(scaled 4097)
[ "$gsize" -lt 64 ] && gsize=64
step "generate_${gsize}" 60 "$runnel" bench generate --size "$gsize" --steps 2 --device "$device"

# 5. The default scenario: 30 s of simulated time, then the whole run (the figures of its
# metrics.json that say where the time went and that the physics held).
default_run() {
  local dir
  dir=$(mktemp -d)
  "$runnel" run data/scenarios/default.toml --device "$device" --out "$dir" --quiet "$@" >&2 || return 1
  python3 - "$dir/metrics.json" <<'PY'
import json, sys
m = json.load(open(sys.argv[1]))
top = sorted(m["kernel_seconds"].items(), key=lambda kv: -kv[1])[:8]
keys = ["device", "steps", "sim_time", "wall_seconds", "particle_steps_per_second", "device_idle_seconds",
        "rain_volume", "eroded_volume", "deposited_volume", "mass_balance_rel"]
print(json.dumps({**{k: m[k] for k in keys}, "kernel_seconds_total": sum(m["kernel_seconds"].values()),
                  "kernel_launches": sum(m["kernel_launches"].values()), "top_kernels": dict(top)}))
PY
}
# The default scenario exchanges with the bed every 10 ms (docs/erosion.md, "Exchange interval");
# the same 30 s with the exchange every step is what the H200 measured before that (docs/gpu.md).
step default_30s 90 bash -c "$(declare -f default_run); runnel=$runnel device=$device default_run --sim-time $(scaled 30)"
step default_30s_exchange_every_step 90 bash -c "$(declare -f default_run); runnel=$runnel device=$device \
  default_run --sim-time $(scaled 30) --set erosion.exchange_interval=0"
step default_30s_dfsph 90 bash -c "$(declare -f default_run); runnel=$runnel device=$device \
  default_run --sim-time $(scaled 30) --set sph.solver=dfsph"

# 6. The test suite, its OpenCL tests on the GPU (the CLI picks the first GPU by itself). The Python
# package's tests need its virtual environment (scripts/setup-python.sh, from PyPI): without one
# they are left out, and the log says so.
exclude=""
if [ ! -x .venv/bin/python ]; then
  exclude='^Python\.'
  echo "gpu-check: tests: no .venv (scripts/setup-python.sh), the Python package's tests left out" >>"$log"
fi
run_tests() {
  local rc
  (cd "$build" && RUNNEL_TEST_DEVICE=$device ctest -j "$(nproc)" --timeout 150 --output-on-failure -LE "fuzz|oclgrind" ${exclude:+-E "$exclude"} ${GPU_CHECK_TESTS:+-R "$GPU_CHECK_TESTS"}) \
    >"$out/tests.log" 2>&1
  rc=$?
  tail -3 "$out/tests.log" >&2
  grep -E '^[0-9]+% tests passed' "$out/tests.log" | python3 -c \
    'import json, sys; print(json.dumps({"all_passed": sys.argv[1] == "0", "summary": sys.stdin.read().strip()}))' "$rc"
}
step tests 200 bash -c "$(declare -f run_tests); build=$build device=$device out=$out exclude='$exclude' \
  GPU_CHECK_TESTS='${GPU_CHECK_TESTS:-}'; run_tests"

# 7. The whole default run.
step default_run 300 bash -c "$(declare -f default_run); runnel=$runnel device=$device default_run"
step default_run_dfsph 120 bash -c "$(declare -f default_run); runnel=$runnel device=$device default_run \
  --set sph.solver=dfsph"

# 8. The viewer at 1280x800, drawn off-screen through EGL (--headless: no display needed), on the
# GPU's own OpenGL where its EGL driver is installed (the entry's gl_renderer says which; Mesa's
# llvmpipe otherwise), simulating on the GPU's OpenCL: --bench's frames/s, simulated seconds per
# wall second and each phase's ms, 20,000 particles of each solver from a short run of the default
# scenario, and the same paused (drawing only).
viewer_bench() {
  local dir solver
  dir=$(mktemp -d)
  echo "{"
  for solver in wcsph dfsph; do
    "$runnel" run data/scenarios/default.toml --set sph.solver=$solver --set rain.rate=5000 \
      --set rain.max_particles=20000 --sim-time 5 --device "$device" --quiet --out "$dir/$solver" \
      >/dev/null 2>&1 || return 1
    echo "\"$solver\": $("$viewer" "$dir/$solver/final.h5" --headless --device "$device" \
      --size 1280x800 --bench --frames 120 2>/dev/null | tail -1),"
  done
  echo "\"paused\": $("$viewer" "$dir/dfsph/final.h5" --headless --device "$device" --size 1280x800 \
    --bench --frames 120 --paused 2>/dev/null | tail -1)}"
}
viewer=$build/runnel-viewer
if [ ! -x "$viewer" ]; then
  entries+=("\"viewer\": {\"skipped\": \"runnel-viewer is not in this build\"}")
else
  step viewer_headless 200 bash -c "$(declare -f viewer_bench); runnel=$runnel viewer=$viewer device=$device viewer_bench"
fi
write_summary
echo "gpu-check: wrote $summary" >&2
