#!/usr/bin/env bash
# Packs what tests/gpu/check.sh needs on a GPU machine that has the NVIDIA
# driver but none of our Debian packages: the Release build's executable and
# test binaries, and the shared libraries they load that a CUDA image lacks
# (ocl-icd's libOpenCL, toml++, GLFW, stb, glvnd's EGL), copied from this
# machine's Debian packages into .gpu/ (git-ignored, ~40 MB).
#
#   tests/gpu/pack.sh            # after ./setup.sh (or any Release build)
#   # then, on the GPU machine, from the repository root:
#   tests/gpu/check.sh OUTDIR
set -euo pipefail
cd "$(dirname "$0")/../.."
build=build/release
[[ -x $build/app/simsols ]] || { echo "pack.sh: build first (./setup.sh)" >&2; exit 2; }
rm -rf .gpu
mkdir -p .gpu/bin .gpu/lib
cp "$build/app/simsols" .gpu/bin/
for t in $(tests/gpu/check.sh --list-tests); do
  [[ -x $build/tests/$t ]] || { echo "pack.sh: $build/tests/$t missing" >&2; exit 2; }
  cp "$build/tests/$t" .gpu/bin/
done
# Libraries outside the C/C++ runtime that the GPU image may not have.
keep='libOpenCL|libtomlplusplus|libglfw|libstb|libEGL\.so|libGLdispatch|libX11|libxcb|libXau|libXdmcp|libbsd|libmd\.so|libz\.so'
for f in .gpu/bin/*; do
  ldd "$f" | awk '$3 ~ /^\// {print $3}'
done | sort -u | grep -E "$keep" | while read -r lib; do cp -L "$lib" .gpu/lib/; done
du -sh .gpu
echo "packed: $(ls .gpu/bin | wc -l) binaries, $(ls .gpu/lib | wc -l) libraries in .gpu/"
