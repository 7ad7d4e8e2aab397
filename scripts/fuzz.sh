#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Fuzzes every reader for longer than the test suite does: SECONDS per target (default 600),
# growing build-asan/fuzz/corpus/<reader> from the committed seeds. Findings (crash-*, leak-*,
# timeout-*) land in build-asan/fuzz/findings/<reader>/.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-600}"
# Build the targets (the configuration scripts/sanitize.sh uses), without running the suite.
CC=clang CXX=clang++ cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRUNNEL_SANITIZE=ON \
  -DRUNNEL_FUZZ=ON -DRUNNEL_BUILD_VIEWER=OFF >/dev/null
cmake --build build-asan -j "$(nproc)" --target fuzz_asc fuzz_png fuzz_npy fuzz_checkpoint fuzz_scenario
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=0:allocator_may_return_null=1:suppressions=$PWD/fuzz/asan.supp}"
for reader in asc png npy checkpoint scenario; do
  mkdir -p "build-asan/fuzz/corpus/$reader" "build-asan/fuzz/findings/$reader"
  echo "fuzzing $reader for ${seconds} s"
  rss=2048
  [ "$reader" = checkpoint ] && rss=6144  # libhdf5 may read a claimed 4 GiB header (fuzz/CMakeLists.txt)
  "build-asan/fuzz/fuzz_$reader" -max_total_time="$seconds" -timeout=60 -rss_limit_mb="$rss" -malloc_limit_mb=8192 \
    -print_final_stats=1 -artifact_prefix="build-asan/fuzz/findings/$reader/" \
    "build-asan/fuzz/corpus/$reader" "fuzz/corpus/$reader" 2>&1 | grep -E "stat::|ERROR|SUMMARY" || true
done
