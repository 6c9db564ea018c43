#!/usr/bin/env bash
# Self-test of check_packages.sh: it must fail, naming the file and its
# package, when setup.sh's list lacks a package the build uses (a header,
# a library, a run-time file, a tool), and when the build used a file that
# no package owns.
# Usage: check_packages_selftest.sh BUILD_DIR SETUP_SH
set -euo pipefail
here=$(dirname "${BASH_SOURCE[0]}")
check=$here/check_packages.sh
command -v dpkg-query >/dev/null || { echo "SKIP: no dpkg here (Debian only)"; exit 77; }
fails=0

# expect_failure NAME REGEX... -- ARGS...: the checker exits 1 and prints a
# line matching each REGEX.
expect_failure() {
  local name=$1 out rc=0
  shift
  local -a want=()
  while [[ $1 != -- ]]; do want+=("$1"); shift; done
  shift
  out=$("$check" "$@" 2>&1) || rc=$?
  if ((rc != 1)); then
    printf 'FAIL %s: exit status %d, expected 1\n%s\n' "$name" "$rc" "$out"
    fails=$((fails + 1))
    return
  fi
  local w
  for w in "${want[@]}"; do
    if ! grep -Eq -- "$w" <<<"$out"; then
      printf 'FAIL %s: no line matches /%s/ in:\n%s\n' "$name" "$w" "$out"
      fails=$((fails + 1))
      return
    fi
  done
  printf 'ok   %s: exit status 1\n' "$name"
  printf '       names /%s/\n' "${want[@]}"
}

# The packages of the bug this test was written for, and one of each kind.
# libfreetype-dev and python3-dev (through libpython3.11-dev) depend on
# zlib1g-dev, and python3-scipy on python3-dev (through python3-pythran), so
# all four go for libz.so and Python.h to be missed.
expect_failure "list without libxrandr-dev, zlib1g-dev, libfreetype-dev, python3-dev, python3-scipy, pocl-opencl-icd, xvfb, cmake" \
  'header /usr/include/X11/extensions/Xrandr\.h is from package libxrandr-dev.*used by app/' \
  'library /usr/lib/[a-z0-9_-]+/libz\.so is from package zlib1g-dev' \
  'header /usr/include/freetype2/ft2build\.h is from package libfreetype-dev.*used by render/plot/' \
  'header /usr/include/python3\.[0-9]+/Python\.h is from package libpython3\.[0-9]+-dev.*used by app/python/' \
  'run-time file /etc/OpenCL/vendors/pocl\.icd .*is from package pocl-opencl-icd' \
  'run-time file /usr/bin/xvfb-run .*is from package xvfb,' \
  'tool /usr/bin/cmake is from package cmake,' \
  'FAIL: .*libxrandr-dev' -- \
  "$1" "$2" --drop libxrandr-dev --drop zlib1g-dev --drop libfreetype-dev --drop python3-dev --drop python3-scipy \
  --drop pocl-opencl-icd --drop xvfb --drop cmake

# The build tool: Ninja, the presets' generator (a Unix Makefiles tree has make).
if grep -qx 'CMAKE_GENERATOR:INTERNAL=Ninja' "$1/CMakeCache.txt"; then
  expect_failure "list without ninja-build" 'tool /usr/bin/ninja is from package ninja-build,' -- \
    "$1" "$2" --drop ninja-build
fi

# A header no package owns (as under /usr/local), in a build tree of its own.
fake=$(mktemp -d)
trap 'rm -rf "$fake"' EXIT
mkdir -p "$fake/build/CMakeFiles/x.dir" "$fake/include"
touch "$fake/include/unowned.h"
grep -E '^(CMAKE_CXX_COMPILER|CMAKE_COMMAND):' "$1/CMakeCache.txt" >"$fake/build/CMakeCache.txt"
printf 'x.o: %s /usr/include/stdio.h\n' "$fake/include/unowned.h" >"$fake/build/CMakeFiles/x.dir/x.o.d"
expect_failure "a header outside every package" \
  "header $fake/include/unowned\.h belongs to no Debian package" -- "$fake/build" "$2"

((fails == 0)) || { echo "check_packages self-test: $fails case(s) failed"; exit 1; }
echo "check_packages self-test: all cases failed as they must"
