#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The test suite once more under AddressSanitizer + UndefinedBehaviorSanitizer (clang), with the
# libFuzzer targets of every reader, each fuzzing a fixed number of inputs (fixed seed) from the
# committed seed corpus. Build tree: build-asan/. Called by scripts/test.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
# PoCL and LLVM keep their compiled kernels for the process's life: not leaks of runnel's.
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=0:abort_on_error=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
CC=clang CXX=clang++ cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRUNNEL_SANITIZE=ON \
  -DRUNNEL_FUZZ=ON -DRUNNEL_BUILD_VIEWER=OFF -DRUNNEL_PYTHON=OFF -DRUNNEL_MPI=OFF >/dev/null  # an ASan module cannot load into python; MPI: tested in the main build
cmake --build build-asan -j "$(nproc)"
cd build-asan
ctest -j "$(nproc)" --output-on-failure
