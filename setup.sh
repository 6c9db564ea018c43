#!/usr/bin/env bash
# SimSols set-up: installs what is missing (Debian 12, apt), builds Release,
# then runs the default experiment (`./setup.sh`) or the test suite
# (`./setup.sh test`). See README.md.
set -euo pipefail

# Debian 12 packages the build, the tests and the headless run need.
# The renderer: GL headers (libgl-dev), EGL (libegl-dev) with Mesa's
# surfaceless EGL and llvmpipe (libegl-mesa0, libgl1-mesa-dri), OSMesa as the
# fallback (libosmesa6, loaded at run time) and GLM. The desktop lab: GLFW,
# Dear ImGui (with its GLFW and OpenGL 3 backends) and, for its scripted
# tests, Xvfb.
PACKAGES=(
  build-essential
  cmake
  # the presets' generator: Ninja builds this tree about 9 % faster than make
  ninja-build
  pkg-config
  ocl-icd-opencl-dev
  opencl-headers
  pocl-opencl-icd
  libtomlplusplus-dev
  libcli11-dev
  libgtest-dev
  zlib1g-dev
  libgl-dev
  libegl-dev
  libegl-mesa0
  libgl1-mesa-dri
  libosmesa6
  libglm-dev
  libglfw3-dev
  libimgui-dev
  # stb_image / stb_image_write: the PNG codec (render/plot/png.cpp)
  libstb-dev
  # FreeType: the text of charts and legends (render/plot/font.cpp)
  libfreetype-dev
  # DejaVu Sans, read at run time by render/plot/font.cpp and the lab's ImGui font
  fonts-dejavu-core
  # VTK for Python: the test that reads a run's ParaView series back (tests/app/cli/test_paraview_vtk.py)
  python3-vtk9
  # Eigen, header-only: a clump's principal axes of inertia (solver/scene/clump.cpp)
  libeigen3-dev
  xvfb
  xauth
  clinfo
  # app/lab/lab_window.cpp includes <GLFW/glfw3native.h> for X11, which includes
  # X11/Xlib.h and X11/extensions/Xrandr.h; libglfw3-dev only recommends these.
  libx11-dev
  libxrandr-dev
  # Boost.Math, header-only: Student's t quantiles (app/experiment/shear_box/study_stats.cpp)
  libboost-math-dev
  # NLopt (C++): the calibration's search on its surrogate (app/experiment/calibration)
  libnlopt-cxx-dev
  # Assimp: grain surface meshes, STL/OBJ (solver/scene/mesh_body.cpp)
  libassimp-dev
  # `import simsols` (app/python): pybind11 and Python's headers to build it,
  # NumPy for its arrays, pytest for its tests (tests/app/python)
  pybind11-dev
  python3-dev
  python3-numpy
  python3-pytest
  # SciPy: Student's t quantiles in the scripts that check the docs' tables
  # against their CSVs (tests/layout/ensemble_stats.py)
  python3-scipy
  # a private one-node Slurm for the cluster test (tests/cluster): slurm-wlm
  # is the controller, node daemon and clients; munge authenticates them
  slurm-wlm
  munge
)

PRESET=release
BIN=build/release/app/simsols
DEFAULT_SCENE=assets/scenes/shear_box.toml
DEFAULT_OUT=results/shear_box
JOBS=${JOBS:-2}

cd "$(dirname "${BASH_SOURCE[0]}")"

say() { printf '==> %s\n' "$*"; }
die() { printf 'setup.sh: %s\n' "$*" >&2; exit 1; }

usage() {
  cat <<EOF
Usage: ./setup.sh [COMMAND] [ARGS...]

Commands:
  run [ARGS...]  (default) install missing packages, build the program and
                 the Python module (Release), open the lab when there is a
                 display, else run the default experiment headless:
                   $BIN run $DEFAULT_SCENE --out $DEFAULT_OUT [ARGS...]
                 ARGS go to 'simsols run' (e.g. --precision double).
  test           install missing packages, build everything (Release), run
                 the whole test suite (ctest --preset $PRESET); exits with
                 its status.
  packages       print the Debian packages this script installs, one per line.
  help           show this text.

Environment:
  JOBS               parallel build jobs (default 2)
  SIMSOLS_CL_DEVICE  OpenCL device to use: gpu, cpu or part of its name
EOF
}

# Prints the packages of PACKAGES that are not installed, one per line.
need_packages() {
  command -v dpkg-query >/dev/null 2>&1 ||
    die "dpkg-query not found: this script supports Debian 12 (apt); install the equivalent of: ${PACKAGES[*]}"
  local pkg
  for pkg in "${PACKAGES[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed"; then
      printf '%s\n' "$pkg"
    fi
  done
}

# Installs the missing packages with apt; does nothing (no network) when none are.
install_packages() {
  local missing
  mapfile -t missing < <(need_packages)
  if ((${#missing[@]} == 0)); then
    say "All ${#PACKAGES[@]} required packages are installed"
    return
  fi
  say "Installing missing packages: ${missing[*]}"
  local -a as_root=()
  if ((EUID != 0)); then
    command -v sudo >/dev/null 2>&1 ||
      die "missing packages (${missing[*]}) and not root, and sudo is not available; run as root or install them: apt-get install ${missing[*]}"
    as_root=(sudo)
  fi
  local -a apt=(env DEBIAN_FRONTEND=noninteractive apt-get -o DPkg::Lock::Timeout=600)
  "${as_root[@]}" "${apt[@]}" update
  "${as_root[@]}" "${apt[@]}" install -y --no-install-recommends "${missing[@]}"
}

# A build tree configured with another generator than the preset's (an
# older checkout used Unix Makefiles) makes CMake refuse to configure: its
# cache goes, the objects are rebuilt.
forget_other_generator() {
  local dir=build/$PRESET want have
  [[ -f $dir/CMakeCache.txt ]] || return 0
  want=$(/usr/bin/python3 -c 'import json, sys
p = [c for c in json.load(open("CMakePresets.json"))["configurePresets"] if c["name"] == sys.argv[1]]
print(p[0]["generator"])' "$PRESET") || die "CMakePresets.json: no generator for the configure preset $PRESET"
  have=$(sed -n 's/^CMAKE_GENERATOR:INTERNAL=//p' "$dir/CMakeCache.txt")
  [[ $have == "$want" ]] && return 0
  say "$dir was configured for '$have', the preset uses '$want': clearing its CMake cache"
  rm -rf "$dir/CMakeCache.txt" "$dir/CMakeFiles"
}

# Configures and builds Release with the CMake preset: with no argument
# everything (the test suite too), else only the targets named.
build() {
  forget_other_generator
  say "Configuring (cmake --preset $PRESET)"
  cmake --preset "$PRESET"
  if (($# > 0)); then
    say "Building $* with $JOBS jobs"
    cmake --build --preset "$PRESET" -j "$JOBS" --target "$@"
  else
    say "Building everything, tests included, with $JOBS jobs"
    cmake --build --preset "$PRESET" -j "$JOBS"
  fi
}

# `import simsols` from anywhere: a .pth file puts the build's python folder
# on the path of Debian's python3 (its site folder as root, else the user's).
link_python_module() {
  local dir="$PWD/build/$PRESET/python" site
  [[ -d $dir ]] || return 0
  if ((EUID == 0)); then
    site=$(/usr/bin/python3 -c 'import site; print(site.getsitepackages()[0])')
  else
    site=$(/usr/bin/python3 -m site --user-site)
  fi
  if mkdir -p "$site" && printf '%s\n' "$dir" >"$site/simsols.pth"; then
    say "Python: import simsols works (python3 finds $dir through $site/simsols.pth)"
  else
    say "warning: could not write $site/simsols.pth; use PYTHONPATH=$dir"
  fi
}

cmd_run() {
  install_packages
  # What the lab and the default experiment use: the program and `import
  # simsols`; `./setup.sh test` builds the test suite on top.
  build simsols simsols_python
  link_python_module
  if [[ -n "${DISPLAY:-}" || -n "${WAYLAND_DISPLAY:-}" ]] && [[ -z "${SIMSOLS_HEADLESS:-}" ]]; then
    say "Display found: opening the lab ($BIN lab); set SIMSOLS_HEADLESS=1 to run the default experiment headless"
    exec "$BIN" lab "$@"
  fi
  [[ -f "$DEFAULT_SCENE" ]] || die "default scene $DEFAULT_SCENE not found"
  say "Running the default experiment: $BIN run $DEFAULT_SCENE --out $DEFAULT_OUT $*"
  "$BIN" run "$DEFAULT_SCENE" --out "$DEFAULT_OUT" "$@"
  # Pictures of the sheared specimen (offscreen OpenGL): the layers as
  # sheared, seen through, and the force chains.
  if [[ -f "$DEFAULT_OUT/summary.txt" ]]; then
    "$BIN" snapshot "$DEFAULT_OUT/checkpoint.bin" --out "$DEFAULT_OUT/specimen.png" \
      --view front --mode transparent --color-by layer --size 1600x900 &&
      "$BIN" snapshot "$DEFAULT_OUT/checkpoint.bin" --out "$DEFAULT_OUT/force_chains.png" \
        --view three-quarter --mode chains --threshold 1 --size 1600x900 ||
      say "warning: no offscreen OpenGL here, so no specimen pictures (see docs/rendering.md)"
  fi
  say "Results are in $PWD/$DEFAULT_OUT (summary.txt, shear.csv, shear_stress.png, shear_ratio.png, dilation.png, specimen.png, force_chains.png, paraview/*.pvd for ParaView, checkpoint.bin, scene.toml)"
  say "Resume with: $BIN run --resume --out $DEFAULT_OUT"
}

cmd_test() {
  install_packages
  build
  link_python_module
  say "Running the test suite (ctest --preset $PRESET)"
  # Two tests at a time, each with one PoCL worker thread (the preset's
  # POCL_MAX_PTHREAD_COUNT=1): two cores, two tests, no thread waiting
  # for a core.
  local rc=0
  ctest --preset "$PRESET" || rc=$?
  if ((rc == 0)); then say "All tests passed"; else say "Tests failed (ctest exit status $rc)"; fi
  return "$rc"
}

main() {
  local cmd=${1:-run}
  (($# > 0)) && shift
  case "$cmd" in
    run) cmd_run "$@" ;;
    test)
      (($# == 0)) || { usage >&2; exit 2; }
      cmd_test
      ;;
    packages) printf '%s\n' "${PACKAGES[@]}" ;;
    help | -h | --help) usage ;;
    -*) cmd_run "$cmd" "$@" ;; # ./setup.sh --precision double = ./setup.sh run --precision double
    *)
      printf 'setup.sh: unknown command: %s\n\n' "$cmd" >&2
      usage >&2
      exit 2
      ;;
  esac
}

main "$@"
