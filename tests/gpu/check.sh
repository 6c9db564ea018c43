#!/usr/bin/env bash
# The GPU check: one short command for a machine with an NVIDIA GPU (its
# driver and OpenCL ICD), run from the repository root after
# tests/gpu/pack.sh packed .gpu/ on the build machine. Each step is bounded,
# logs to OUTDIR/check.log and appends its figures; a failing step is
# reported and the next one runs. Exit status: the number of failed steps.
#
#   tests/gpu/check.sh OUTDIR [--quick]     # --quick: smaller sizes (a PoCL dry run)
#   tests/gpu/check.sh --list-tests         # the test binaries it runs
#
# Steps (docs/performance.md, "The GPU check"):
#   device     OpenCL platforms and devices, nvidia-smi
#   physics    the contact, wall, conservation, determinism and stability
#              tests on the GPU (one particle per work item, LANES == 1)
#   sharing    test_particle_bridge with CL-GL sharing required
#              (SIMSOLS_EXPECT_GL_SHARING=1): fails on the host-copy path
#   bench      simsols bench at 50 k, 1 M and 4 M beads, float and double
#   shear      the paper's 2.38 mm direct shear test (5 000 beads), 40 815
#              steps as in tests/bench/shear_vs_liggghts.sh, timed
#   render     simsols bench --render and --render --stereo
set -uo pipefail

TESTS="test_hertz test_restitution test_friction test_rolling test_walls test_conservation
test_determinism test_neighbors test_stability_contact test_particle_bridge test_renderer"
if [[ ${1:-} == --list-tests ]]; then echo $TESTS; exit 0; fi
out=${1:?usage: tests/gpu/check.sh OUTDIR [--quick]}
quick=${2:-}
cd "$(dirname "$0")/../.."
root=$PWD
mkdir -p "$out"
out=$(cd "$out" && pwd)
log=$out/check.log
bin=$root/.gpu/bin
[[ -x $bin/simsols ]] || { echo "check.sh: run tests/gpu/pack.sh on the build machine first" >&2; exit 2; }
export LD_LIBRARY_PATH=$root/.gpu/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
export SIMSOLS_ASSETS=$root/assets
export POCL_CACHE_DIR=$out/pocl-cache
# The NVIDIA OpenCL driver, registered for ocl-icd when the image has no
# /etc/OpenCL/vendors entry for it; the NVIDIA EGL vendor library likewise.
if [[ ! -e /etc/OpenCL/vendors/nvidia.icd ]] && ldconfig -p | grep -q libnvidia-opencl.so.1; then
  mkdir -p "$out/icd" && echo libnvidia-opencl.so.1 > "$out/icd/nvidia.icd"
  export OCL_ICD_VENDORS=$out/icd
fi
for f in /usr/share/glvnd/egl_vendor.d/10_nvidia.json /usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json; do
  [[ -e $f ]] && { export __EGL_VENDOR_LIBRARY_FILENAMES=$f; break; }
done
if [[ $quick == --quick ]]; then
  sizes="5000 20000"; budget=2e6; shear_steps=2000
else
  export SIMSOLS_CL_DEVICE=${SIMSOLS_CL_DEVICE:-gpu}
  sizes="50000 1000000 4000000"; budget=5e8; shear_steps=40815
fi
failed=0
# The whole check ends within GPU_CHECK_SECONDS (default 540: a 10-minute
# device call with room for the start); each step within its own limit too.
deadline=$((SECONDS + ${GPU_CHECK_SECONDS:-540}))
step() {  # step NAME SECONDS COMMAND...
  local name=$1 limit=$2; shift 2
  local t0=$SECONDS left=$((deadline - SECONDS))
  ((left < limit)) && limit=$left
  if ((limit < 5)); then
    echo "=== $name: SKIPPED, no time left" | tee -a "$log"; failed=$((failed + 1)); return
  fi
  echo "=== $name: $*" | tee -a "$log"
  local -a cmd=("$@")
  declare -F "$1" >/dev/null && cmd=(bash -c '"$@"' step "$@")
  if timeout "$limit" "${cmd[@]}" >>"$log" 2>&1; then
    echo "=== $name: ok ($((SECONDS - t0)) s)" | tee -a "$log"
  else
    echo "=== $name: FAILED, status $? ($((SECONDS - t0)) s)" | tee -a "$log"
    failed=$((failed + 1))
  fi
}

device_info() {
  command -v nvidia-smi >/dev/null && nvidia-smi
  "$bin/simsols" bench --sizes 1000 --precision float --repeat 1 --budget 1e4
}
physics() {
  local t rc=0
  for t in $TESTS; do
    [[ $t == test_particle_bridge || $t == test_renderer ]] && continue
    echo "--- $t"
    "$bin/$t" --gtest_brief=1 || rc=1
  done
  return $rc
}
shear() {
  local scene=$out/shear_2.38mm.toml
  assets/crosscheck/liggghts/scene_2.38mm.sh "$scene" || return 1
  local t0
  t0=$(date +%s.%N)
  "$bin/simsols" run "$scene" --out "$out/shear" --stop-after "$shear_steps" -q || return 1
  awk -v t0="$t0" -v t1="$(date +%s.%N)" -v s="$shear_steps" \
    'BEGIN { printf "shear: 5000 beads x %d steps in %.1f s (kernel build included): %.3g particle-steps/s\n", s, t1 - t0, 5000 * s / (t1 - t0) }'
}

# the step functions run under timeout, in a child bash
export bin out TESTS shear_steps
export -f device_info physics shear

step device 60 device_info
step physics 240 physics
step sharing 60 env SIMSOLS_EXPECT_GL_SHARING=1 "$bin/test_particle_bridge"
step renderer-tests 60 "$bin/test_renderer"
step bench 240 "$bin/simsols" bench --sizes $sizes --precision float double --repeat 3 --budget $budget
step shear 120 shear
step render 90 "$bin/simsols" bench --render --sizes 5000 100000 --repeat 3
step stereo 60 "$bin/simsols" bench --render --stereo --sizes 5000 --repeat 3
# the figures: everything but the tests' own output
awk '/^=== (physics|sharing|renderer-tests): [^oF]/ {skip = 1} /^===/ && / (ok|FAILED|SKIPPED)/ {skip = 0}
     !skip' "$log" > "$out/summary.txt"
echo "check.sh: $failed step(s) failed; log in $log, figures in $out/summary.txt"
exit "$failed"
