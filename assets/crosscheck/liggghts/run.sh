#!/usr/bin/env bash
# The SimSols direct shear test of the 2.38125 mm specimen (8 layers of
# 25 x 25 glass beads, 160 kPa) rerun in LIGGGHTS, from the same beads.
#
#   run.sh [--simsols BIN | --scene SCENE.resolved.toml] [--rows N] OUTDIR
#
#   --simsols BIN  the simsols executable: the specimen is built by
#                  `BIN run --stop-after 1` from assets/scenes/shear_box.toml
#                  with diameter 2.38125 mm and 8 layers (the scene of
#                  `simsols campaign --sizes 2.38125 --stresses 160`)
#   --scene FILE   use this scene instead (a scene.resolved.toml, every bead
#                  listed), e.g. one from a campaign folder
#   --rows N       stop the shear after N rows (of 300 over 6 mm)
#
# Needs python3 and liggghts (Debian/Ubuntu package `liggghts`) on PATH, or
# LIGGGHTS=/path/to/liggghts. Runs one process; prefix with `nice -n 10` to
# be kind to other work. Writes OUTDIR/liggghts_shear.csv, shear.csv (SimSols
# layout), summary.txt, phases.txt, rows.txt, log.liggghts and gen/ (inputs).
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
simsols="" scene="" rows=1000000000 out=""
while (($#)); do
  case "$1" in
    --simsols) simsols=$2; shift 2 ;;
    --scene) scene=$2; shift 2 ;;
    --rows) rows=$2; shift 2 ;;
    -h|--help) sed -n '2,19p' "$0"; exit 0 ;;
    -*) echo "run.sh: unknown option $1" >&2; exit 2 ;;
    *) out=$1; shift ;;
  esac
done
if [[ -z "$out" || ( -z "$simsols" && -z "$scene" ) ]]; then
  echo "usage: run.sh [--simsols BIN | --scene SCENE.resolved.toml] [--rows N] OUTDIR" >&2
  exit 2
fi
liggghts=${LIGGGHTS:-liggghts}
command -v "$liggghts" >/dev/null || { echo "run.sh: $liggghts not found (apt-get install liggghts)" >&2; exit 2; }
mkdir -p "$out"
out=$(cd "$out" && pwd)

if [[ -z "$scene" ]]; then
  "$here/scene_2.38mm.sh" "$out/scene.toml"
  rm -rf "$out/simsols_start"
  "$simsols" run "$out/scene.toml" --out "$out/simsols_start" --stop-after 1 -q > /dev/null
  scene=$out/simsols_start/scene.resolved.toml
fi

python3 "$here/gen.py" "$scene" "$out/gen"
start=$(date +%s)
"$liggghts" -in "$here/shear.in" -var dir "$out/gen" -var out "$out" -var max_rows "$rows" \
  -log "$out/log.liggghts" > "$out/screen.txt" 2>&1 ||
  { echo "run.sh: liggghts failed, see $out/log.liggghts" >&2; tail -5 "$out/log.liggghts" >&2; exit 1; }
echo "wall_seconds = $(( $(date +%s) - start ))" > "$out/wall.txt"
python3 "$here/post.py" "$out" "$out/gen"
cat "$out/wall.txt" >> "$out/summary.txt"
