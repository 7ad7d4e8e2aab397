#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Packs the Release build for a GPU machine that cannot build runnel itself (no network, none of
# Debian's -dev packages): .gpu/bundle.tar.xz holds runnel, runnel-viewer, runnel_tests and the
# CTest files of build/, and every shared library they load except the C library's own (glibc,
# libstdc++ and libgcc_s come from the machine; the binaries need glibc 2.35) and the OpenGL/EGL
# dispatch libraries, which must be the machine's so that its GPU driver draws (runnel-viewer
# --headless). The binaries find the libraries
# through an RPATH set here ($ORIGIN-relative, inherited by the libraries they load), so no
# LD_LIBRARY_PATH leaks into the machine's own programs. scripts/gpu-check.sh unpacks it.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh >/dev/null
bash scripts/build.sh >/dev/null

stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
mkdir -p "$stage/.gpu/lib" "$stage/build/tests"
binaries=(build/runnel build/runnel-viewer build/tests/runnel_tests)
ldd "${binaries[@]}" | awk '$2 == "=>" && $3 ~ /^\// { print $3 }' | sort -u | while read -r lib; do
  case "$(basename "$lib")" in
    libc.so.* | libm.so.* | libpthread.so.* | libdl.so.* | librt.so.* | libresolv.so.* | ld-linux*) ;;
    libstdc++.so.* | libgcc_s.so.*) ;;
    libGL.so.* | libGLX.so.* | libEGL.so.* | libGLdispatch.so.* | libOpenGL.so.*) ;;
    *) cp -L "$lib" "$stage/.gpu/lib/" ;;
  esac
done
cp build/runnel build/runnel-viewer build/CTestTestfile.cmake "$stage/build/"
cp build/tests/runnel_tests build/tests/*.cmake "$stage/build/tests/"
patchelf --force-rpath --set-rpath '$ORIGIN/../.gpu/lib' "$stage/build/runnel"
patchelf --force-rpath --set-rpath '$ORIGIN/../.gpu/lib' "$stage/build/runnel-viewer"
patchelf --force-rpath --set-rpath '$ORIGIN/../../.gpu/lib' "$stage/build/tests/runnel_tests"
# The source tree the binaries were built in (tests find data/ and the CLI through it).
echo "$PWD" >"$stage/.gpu/built-in"
mkdir -p .gpu
tar -C "$stage" -cf - .gpu build | xz -T"$(nproc)" -6 >.gpu/bundle.tar.xz
echo "gpu-bundle: .gpu/bundle.tar.xz, $(du -m .gpu/bundle.tar.xz | cut -f1) MiB, $(ls "$stage/.gpu/lib" | wc -l) libraries"
