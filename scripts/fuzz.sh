#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Fuzzes every reader and the Python entry points for longer than the test suite does: SECONDS
# per target (default 600),
# growing build-asan/fuzz/corpus/<reader> from the committed seeds. Findings (crash-*, leak-*,
# timeout-*) land in build-asan/fuzz/findings/<reader>/.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-600}"
# Build the targets (the configuration scripts/sanitize.sh uses), without running the suite.
CC=clang CXX=clang++ cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRUNNEL_SANITIZE=ON \
  -DRUNNEL_FUZZ=ON -DRUNNEL_BUILD_VIEWER=OFF >/dev/null
cmake --build build-asan -j "$(nproc)" --target fuzz_asc fuzz_png fuzz_npy fuzz_checkpoint fuzz_scenario fuzz_sweep fuzz_series
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=0:allocator_may_return_null=1:suppressions=$PWD/fuzz/asan.supp}"
for reader in asc png npy checkpoint scenario sweep series; do
  mkdir -p "build-asan/fuzz/corpus/$reader" "build-asan/fuzz/findings/$reader"
  echo "fuzzing $reader for ${seconds} s"
  rss=2048
  { [ "$reader" = checkpoint ] || [ "$reader" = series ]; } && rss=6144  # libhdf5 may read a claimed 4 GiB header (fuzz/CMakeLists.txt)
  "build-asan/fuzz/fuzz_$reader" -max_total_time="$seconds" -timeout=60 -rss_limit_mb="$rss" -malloc_limit_mb=8192 \
    -print_final_stats=1 -artifact_prefix="build-asan/fuzz/findings/$reader/" \
    "build-asan/fuzz/corpus/$reader" "fuzz/corpus/$reader" 2>&1 | grep -E "stat::|ERROR|SUMMARY" || true
done
# The Python entry points, through their harness (python/tests/test_fuzz_entry_points.py) on the
# normal build's module: about 1,400 calls a second.
# The interpreter: $PYTHON, else the virtual environment's (scripts/setup-python.sh), else python3.
python="${PYTHON:-}"
[ -z "$python" ] && [ -x .venv/bin/python ] && python=.venv/bin/python
python="${python:-python3}"
if [ -d build/python/runnel ]; then
  echo "fuzzing the Python entry points for about ${seconds} s"
  RUNNEL_FUZZ_ITERATIONS=$((seconds * 1400)) PYTHONPATH="$PWD/build/python" \
    "$python" -m pytest -q -p no:cacheprovider python/tests/test_fuzz_entry_points.py 2>&1 | tail -1
fi
