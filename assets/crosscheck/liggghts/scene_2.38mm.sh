#!/usr/bin/env bash
# Writes the paper's 2.38125 mm direct shear scene (8 layers of 25 x 25
# glass beads, 160 kPa; the scene of `simsols campaign --sizes 2.38125
# --stresses 160`) to OUTFILE, from assets/scenes/shear_box.toml. Shared by
# run.sh, tests/bench/shear_vs_liggghts.sh and tests/gpu/check.sh.
#
#   scene_2.38mm.sh OUTFILE
set -euo pipefail
out=${1:?usage: scene_2.38mm.sh OUTFILE}
root=$(cd "$(dirname "$0")/../../.." && pwd)
sed -e 's/^diameter = 6.35e-3 .*/diameter = 2.38125e-3/' -e 's/^layers = 4$/layers = 8/' \
  "$root/assets/scenes/shear_box.toml" > "$out"
grep -q '^diameter = 2.38125e-3' "$out" && grep -q '^layers = 8' "$out" ||
  { echo "scene_2.38mm.sh: could not set the specimen in shear_box.toml" >&2; exit 1; }
