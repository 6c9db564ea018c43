#!/usr/bin/env bash
# test_slurm.sh SIMSOLS - a campaign on a real Slurm cluster against
# the same campaign run locally (app/experiment/cluster.h, docs/cluster.md).
#
# Starts a private one-node Slurm in a temporary folder (local_slurm.sh:
# munged, slurmctld, slurmd on localhost), emits a 2-test campaign with
# `--emit slurm`, submits it with the emitted submit.sh (the array and the
# collecting job after it), requeues the first task while it runs (Slurm
# stops it, it checkpoints, it runs again and resumes), waits for all,
# then runs the same campaign locally and compares: every test's rows
# (shear.csv) byte for byte, every summary and the campaign's summary.csv
# except the wall times. Then a small calibration as a chain of arrays
# (each collecting job submits the next batch's array, passing on the
# sbatch arguments), compared with the same calibration run locally.
# Every daemon is stopped on the way out, whatever happens.
set -euo pipefail
export PATH=$PATH:/usr/sbin:/sbin  # the daemons, for a user whose PATH lacks them

SIMSOLS=$(realpath "$1")
HERE=$(cd "$(dirname "$0")" && pwd)
WORK=$(mktemp -d /tmp/simsols_slurm.XXXXXX)
CLUSTER=$WORK/cluster

fail() { echo "FAIL: $*" >&2; exit 1; }
cleanup() {
  bash "$HERE/local_slurm.sh" stop "$CLUSTER" >&2 || true
  rm -rf "$WORK"
}
trap cleanup EXIT

if [[ $(id -u) != 0 ]]; then
  echo "SKIP: slurmd runs jobs as their users and must start as root"
  exit 77
fi
for tool in slurmctld slurmd sbatch munged; do
  command -v "$tool" > /dev/null || fail "$tool not found: setup.sh installs slurm-wlm and munge"
done

eval "$(bash "$HERE/local_slurm.sh" start "$CLUSTER")"
echo "cluster up: $SLURM_CONF"

# the paper's 6.35 mm test (the built-in base) at two stresses, sheared 0.3 mm
ARGS=(campaign --sizes 6.35 --stresses 80,160 --displacement 0.3)
"$SIMSOLS" "${ARGS[@]}" --out "$WORK/slurm_run" --emit slurm
[[ -x $WORK/slurm_run/slurm/submit.sh ]] || fail "no submit.sh"
grep -q '^#SBATCH --array=0-1$' "$WORK/slurm_run/slurm/array.sbatch" || fail "not a 2-task array"

submitted=$("$WORK/slurm_run/slurm/submit.sh")
echo "$submitted"
[[ $submitted =~ ^array\ job\ ([0-9]+),\ collect\ job\ [0-9]+$ ]] || fail "submit.sh said: $submitted"
ARRAY=${BASH_REMATCH[1]}
LOG0=$WORK/slurm_run/slurm/logs/task_0.out
deadline=$((SECONDS + 300))
until grep -q 'shearing at' "$LOG0" 2>/dev/null; do
  ((SECONDS < deadline)) || fail "task 0 did not start shearing within 5 minutes"
  sleep 0.2
done
scontrol requeue "${ARRAY}_0"
echo "requeued task 0 while it was shearing"
deadline=$((SECONDS + 900))
while [[ -n $(squeue -h -o %i) ]]; do
  ((SECONDS < deadline)) || { squeue; fail "the jobs did not finish within 15 minutes"; }
  sleep 2
done
for f in "$WORK"/slurm_run/slurm/logs/*.out; do echo "--- $f"; tail -n 5 "$f"; done
sacct_state=$(scontrol show job 2>/dev/null | grep -o 'JobState=[A-Z]*' | sort | uniq -c || true)
echo "job states: ${sacct_state:-(purged)}"
[[ -f $WORK/slurm_run/summary.csv ]] || fail "the collecting job wrote no summary.csv"
grep -q 'interrupted' "$LOG0" || fail "task 0 was not stopped by the requeue"
grep -q '] resumed at step' "$LOG0" || fail "the requeued task 0 did not resume from its checkpoint"
grep -q "campaign collected: 2 tests" "$WORK/slurm_run/slurm/logs/collect.out" ||
  fail "collect.out does not say the campaign was collected"

"$SIMSOLS" "${ARGS[@]}" --out "$WORK/local_run" -q > /dev/null

# The same tests, the same numbers: only the wall times differ.
drop_wall() { grep -v '^wall_seconds' "$1"; }
drop_last_column() { sed 's/,[^,]*$//' "$1"; }
for t in d6.35mm_80kPa d6.35mm_160kPa; do
  cmp "$WORK/slurm_run/$t/shear.csv" "$WORK/local_run/$t/shear.csv" || fail "$t: rows differ"
  diff <(drop_wall "$WORK/slurm_run/$t/summary.txt") <(drop_wall "$WORK/local_run/$t/summary.txt") ||
    fail "$t: summaries differ"
done
head -1 "$WORK/local_run/summary.csv" | grep -q ',wall_seconds$' || fail "summary.csv's last column moved"
diff <(drop_last_column "$WORK/slurm_run/summary.csv") <(drop_last_column "$WORK/local_run/summary.csv") ||
  fail "summary.csv differs"
for png in d6.35mm_stress.png mohr_coulomb.png; do
  [[ -s $WORK/slurm_run/$png ]] || fail "the collecting job drew no $png"
done
echo "PASS: the Slurm array and its collecting job give the local campaign's results"

# A calibration is a chain of arrays (round 0, round 1, the replicates):
# each collecting job writes and submits the next batch's job with the
# sbatch arguments it was given; the last writes the report, which must
# equal a local run's.
CAL=$WORK/cal
mkdir -p "$CAL"
{
  echo "strain,stress_ratio"
  for i in $(seq 0 10); do awk -v i="$i" 'BEGIN { printf "%g,%g\n", 0.003 * i, 1.2 * (1 - exp(-0.6 * i)) }'; done
} > "$CAL/measured.csv"
cat > "$CAL/cal.toml" <<EOF
[calibration]
name = "chain"
budget = 6
rounds = 2
replicates = 2
points = 5
[[parameters]]
name = "mu_s"
key = "materials.beads.sliding_friction"
min = 0.1
max = 0.6
[[targets]]
name = "t"
scene = "$(realpath "$HERE/../../assets/tests/periodic_triaxial_small.toml")"
data = "measured.csv"
set = { "periodic_cell.axial_strain" = 0.03 }
x = { column = "strain", unit = "-", quantity = "axial_strain" }
[[targets.y]]
column = "stress_ratio"
unit = "-"
quantity = "stress_ratio"
EOF
"$SIMSOLS" calibrate "$CAL/cal.toml" --out "$CAL/slurm_run" -q --emit slurm
grep -qx "batch = 'round0'" "$CAL/slurm_run/slurm/manifest.toml" || fail "the first job is not round 0's"
"$CAL/slurm_run/slurm/submit.sh" --comment=chain
deadline=$((SECONDS + 600))
until [[ -f $CAL/slurm_run/parameters.csv && -z $(squeue -h -o %i) ]]; do
  ((SECONDS < deadline)) || { squeue; tail -n 20 "$CAL/slurm_run/slurm/logs/collect.out"; fail "the calibration's chain did not finish within 10 minutes"; }
  sleep 1
done
tail -n 8 "$CAL/slurm_run/slurm/logs/collect.out"
[[ $(grep -c "next batch's job is written" "$CAL/slurm_run/slurm/logs/collect.out") == 2 ]] ||
  fail "collect.out does not show round 1's and the replicates' jobs written"
grep -qx "batch = 'replicates'" "$CAL/slurm_run/slurm/manifest.toml" || fail "the last job is not the replicates'"
"$SIMSOLS" calibrate "$CAL/cal.toml" --out "$CAL/local_run" -q > /dev/null
for f in parameters.csv design.csv curves.csv; do
  cmp "$CAL/slurm_run/$f" "$CAL/local_run/$f" || fail "the calibration's $f differs from the local run's"
done
echo "PASS: the calibration's chain of arrays gives the local calibration"
