#!/usr/bin/env bash
# SimSols against LIGGGHTS on the same work, side by side: the paper's
# 2.38125 mm direct shear specimen (8 layers of 25 x 25 glass beads, 5 000
# beads, 160 kPa), the same bead positions, contact model, walls and
# programme (settle, consolidate under the servo platen, shear; LIGGGHTS'
# input is assets/crosscheck/liggghts/shear.in), for the same number of steps.
# Rounds alternate the codes (LIGGGHTS on MPI ranks, SimSols float, SimSols
# double) so the machine's drift shows in each one's range.
#
#   tests/bench/shear_vs_liggghts.sh [--rounds N] [--rows R] [--ranks K] [--simsols BIN] OUTDIR
#
#   --rounds N   rounds of the three runs (default 3); medians are printed
#   --rows R     shear rows LIGGGHTS runs (of 300 over 6 mm; default 8)
#   --ranks K    LIGGGHTS MPI ranks (default 2, the domain split along x)
#   --simsols B  the simsols executable (default build/release/app/simsols)
#
# LIGGGHTS runs its programme (settle until quiet, consolidate until quiet,
# R rows of shear); its step count is the work, and SimSols runs exactly as
# many steps of its own programme from the same beads (--stop-after).
# Each run is timed whole (start-up included: reading the beads for
# LIGGGHTS, building the kernels for SimSols, about 1 s each).
# Needs liggghts and mpirun (Debian: apt-get install --no-install-recommends
# liggghts openmpi-bin) and python3. Writes OUTDIR/runs.csv and OUTDIR/summary.txt.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
rounds=3 rows=8 ranks=2 simsols=$root/build/release/app/simsols out=""
while (($#)); do
  case "$1" in
    --rounds) rounds=$2; shift 2 ;;
    --rows) rows=$2; shift 2 ;;
    --ranks) ranks=$2; shift 2 ;;
    --simsols) simsols=$2; shift 2 ;;
    -h | --help) sed -n '2,24p' "$0"; exit 0 ;;
    -*) echo "shear_vs_liggghts.sh: unknown option $1" >&2; exit 2 ;;
    *) out=$1; shift ;;
  esac
done
[[ -n $out ]] || { echo "usage: shear_vs_liggghts.sh [--rounds N] [--rows R] [--ranks K] OUTDIR" >&2; exit 2; }
for c in liggghts mpirun python3; do
  command -v $c >/dev/null || { echo "shear_vs_liggghts.sh: $c not found (apt-get install --no-install-recommends liggghts openmpi-bin python3)" >&2; exit 2; }
done
[[ -x $simsols ]] || { echo "shear_vs_liggghts.sh: $simsols not found (build with ./setup.sh)" >&2; exit 2; }
mkdir -p "$out"
out=$(cd "$out" && pwd)
lig=$root/assets/crosscheck/liggghts
now() { date +%s.%N; }

# The specimen: SimSols builds it, both codes start from its beads.
"$lig/scene_2.38mm.sh" "$out/scene.toml"
rm -rf "$out/start"
"$simsols" run "$out/scene.toml" --out "$out/start" --stop-after 1 -q > /dev/null
scene=$out/start/scene.resolved.toml
python3 "$lig/gen.py" "$scene" "$out/gen" > "$out/gen.txt"
beads=$(awk '$2 == "nbeads" {print $4}' "$out/gen/params.in")

echo "round,code,steps,wall_s,particle_steps_per_s" > "$out/runs.csv"
for ((r = 1; r <= rounds; r++)); do
  d=$out/liggghts_$r
  rm -rf "$d" && mkdir -p "$d"
  t0=$(now)
  mpirun --allow-run-as-root --oversubscribe -np "$ranks" liggghts -in "$lig/shear.in" \
    -var dir "$out/gen" -var out "$d" -var max_rows "$rows" -var px "$ranks" \
    -log "$d/log.liggghts" > "$d/screen.txt" 2>&1
  t1=$(now)
  steps=$(awk 'NF && $1 !~ /^#/ {s = $2} END {print s}' "$d/rows.txt")
  echo "$r,liggghts_${ranks}_ranks,$steps,$(awk -v a="$t0" -v b="$t1" 'BEGIN{print b-a}'),$(awk -v a="$t0" -v b="$t1" -v s="$steps" -v n="$beads" 'BEGIN{printf "%.4g", n*s/(b-a)}')" >> "$out/runs.csv"
  for p in float double; do
    rm -rf "$out/simsols_${p}_$r"
    t0=$(now)
    "$simsols" run "$scene" --out "$out/simsols_${p}_$r" --precision "$p" --stop-after "$steps" -q > /dev/null
    t1=$(now)
    echo "$r,simsols_$p,$steps,$(awk -v a="$t0" -v b="$t1" 'BEGIN{print b-a}'),$(awk -v a="$t0" -v b="$t1" -v s="$steps" -v n="$beads" 'BEGIN{printf "%.4g", n*s/(b-a)}')" >> "$out/runs.csv"
  done
  tail -3 "$out/runs.csv"
done

python3 - "$out/runs.csv" "$beads" "$ranks" > "$out/summary.txt" <<'PY'
import csv, statistics, sys
rows = list(csv.DictReader(open(sys.argv[1])))
codes = []
for r in rows:
    if r["code"] not in codes: codes.append(r["code"])
rate = {c: [float(r["particle_steps_per_s"]) for r in rows if r["code"] == c] for c in codes}
ref = statistics.median(rate[codes[0]])
print(f"{sys.argv[2]} beads, {len(rows) // len(codes)} rounds; particle-steps/s, median (range); x = against {codes[0]}")
for c in codes:
    m = statistics.median(rate[c])
    print(f"{c:22s} {m:.3g} ({min(rate[c]):.3g}-{max(rate[c]):.3g})  x {m / ref:.2f}")
PY
cat "$out/summary.txt"
