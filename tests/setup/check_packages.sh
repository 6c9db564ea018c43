#!/usr/bin/env bash
# Checks that setup.sh installs every Debian package the build and the tests
# use. It reads what the build really used from the build tree: the system
# headers in the compiler's dependency files (*.o.d, compiler_depend.make
# under Unix Makefiles; Ninja's own log, `ninja -t deps`, under Ninja),
# the libraries and tools of the link commands (build.ninja or link.txt),
# the compiler's implicit libraries,
# the shared libraries the built executables load (ldd), the tools in
# CMakeCache.txt, and the files loaded at run time listed in RUNTIME below.
# Each file's owner (dpkg -S) must be
#   - in setup.sh's PACKAGES (`setup.sh packages`), or
#   - pulled in from them through Depends/Pre-Depends, recursively (not
#     Recommends/Suggests); of alternatives `a | b` the first one installed
#     here counts, a virtual package counts as its installed providers, or
#   - in the minimal Debian 12 base: what `mmdebstrap bookworm` installs by
#     default (variant debootstrap = important): the Essential:yes packages
#     and those of Priority required or important, with their Depends.
# A file no package owns (e.g. under /usr/local) is an error too.
#
# Usage: check_packages.sh BUILD_DIR SETUP_SH [--drop PACKAGE]...
#   --drop PACKAGE  check as if PACKAGE were not in the list (self-test).
# Exit status: 0 all covered, 1 something is not, 2 usage, 77 no dpkg.
# shellcheck disable=SC2206,SC2004,SC2016 # package lists split on spaces; out[$p] is an associative array; awk programs in single quotes
set -euo pipefail

die() { printf 'check_packages: %s\n' "$*" >&2; exit 2; }
(($# >= 2)) || die "usage: $0 BUILD_DIR SETUP_SH [--drop PACKAGE]..."
BUILD=$(realpath -e "$1") || die "no build directory $1"
SETUP=$(realpath -e "$2") || die "no $2"
SRC=$(dirname "$SETUP")
shift 2
declare -A DROP=()
while (($#)); do
  [[ $1 == --drop && $# -ge 2 ]] || die "unknown argument $1"
  DROP[$2]=1
  shift 2
done
command -v dpkg-query >/dev/null || { echo "check_packages: SKIP, no dpkg here (Debian only)"; exit 77; }
[[ -f $BUILD/CMakeCache.txt ]] || die "$BUILD is not a CMake build directory"

# Loaded at run time, not seen by the linker: what|why. lib: is a shared
# library name (ldconfig), exe: a command, anything else a path.
MA=$(dpkg-architecture -qDEB_HOST_MULTIARCH 2>/dev/null || gcc -print-multiarch)
RUNTIME=(
  "/etc/OpenCL/vendors/pocl.icd|the OpenCL loader finds PoCL through it"
  "lib:libOSMesa.so.8|render/gl/gl_context.cpp dlopens OSMesa"
  "/usr/share/glvnd/egl_vendor.d/50_mesa.json|libglvnd's EGL finds Mesa through it"
  "lib:libEGL_mesa.so.0|Mesa's EGL (surfaceless)"
  "/usr/lib/$MA/dri/swrast_dri.so|Mesa's llvmpipe driver"
  "exe:xvfb-run|tests/app/lab/test_lab.cpp runs the lab under it"
  "exe:Xvfb|xvfb-run starts it"
  "exe:xauth|xvfb-run calls it"
  "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf|render/plot/font.cpp draws text with it"
  "/usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf|render/plot/font.cpp draws bold text with it"
  "exe:/usr/bin/python3|tests/app/cli/test_paraview_vtk.py runs under Debian's Python"
  "/usr/lib/python3/dist-packages/vtkmodules/__init__.py|tests/app/cli/test_paraview_vtk.py reads the ParaView series with VTK"
  "/usr/lib/python3/dist-packages/numpy/__init__.py|the Python module's arrays (app/python) and its tests"
  "/usr/lib/python3/dist-packages/pytest/__init__.py|ctest runs tests/app/python under pytest"
  "exe:slurmctld|tests/cluster/local_slurm.sh starts the controller"
  "exe:slurmd|tests/cluster/local_slurm.sh starts the node"
  "exe:sbatch|tests/cluster/test_slurm.sh submits the campaign's array"
  "exe:munged|tests/cluster/local_slurm.sh authenticates Slurm with it"
  "exe:mungekey|tests/cluster/local_slurm.sh creates the key"
)

cache() { sed -n "s/^$1:[A-Z]*=//p" "$BUILD/CMakeCache.txt"; }
CXX=$(cache CMAKE_CXX_COMPILER)

declare -A WHY=() # file -> where it came from (header, library, tool, runtime)
ERRORS=()
declare -A NOTE=() # file -> why it is needed, for run-time files
add() { [[ -n ${WHY[$1]:-} ]] || { WHY[$1]=$2; NOTE[$1]=${3:-}; }; }

# Headers: every absolute dependency outside the source and build trees,
# as OBJECT<TAB>HEADER lines in $PAIRS. Make-style files and `ninja -t
# deps` both name an object as a word ending in ':' followed by its
# dependencies (Ninja keeps no .d files: it reads them into .ninja_deps).
PAIRS=$(mktemp)
trap 'rm -f "$PAIRS"' EXIT
NINJA= # the build tool of a Ninja tree; empty under Unix Makefiles
[[ -f $BUILD/build.ninja ]] && NINJA=$(cache CMAKE_MAKE_PROGRAM)
dependency_text() {
  if [[ -n $NINJA ]]; then
    "$NINJA" -C "$BUILD" -t deps
  else
    find "$BUILD" \( -name '*.o.d' -o -name compiler_depend.make \) -exec cat {} +
  fi
}
dependency_text | awk '
  { for (i = 1; i <= NF; i++)
      if ($i ~ /:$/) obj = substr($i, 1, length($i) - 1)
      else if ($i ~ /^\//) print obj "\t" $i }' | sort -u >"$PAIRS"
mapfile -t deps < <(cut -f2 "$PAIRS" | sort -u)
NHEADERS=0
declare -A RAW=() # header, normalised -> as the dependency files spell it
if ((${#deps[@]})); then
  mapfile -t norm < <(realpath -s -m -- "${deps[@]}")
  for i in "${!deps[@]}"; do
    p=${norm[i]}
    [[ $p == "$SRC"/* || $p == "$BUILD"/* || -n ${RAW[$p]:-} ]] && continue
    RAW[$p]=${deps[i]}
    add "$p" header
    NHEADERS=$((NHEADERS + 1))
  done
fi
((NHEADERS > 0)) || die "no dependency files with system headers under $BUILD: build it first"

# Libraries and tools: the link and archive commands (-lNAME, absolute
# paths, the programs: each command's first word and each after '&&') and
# the compiler's implicit libraries. Ninja keeps them in build.ninja
# (`ninja -t commands`, the lines that start with ':'), Unix Makefiles in
# link.txt files.
add_libname() { # -lNAME, as the linker finds it
  local f
  for f in "lib$1.so" "lib$1.a"; do
    f=$("$CXX" -print-file-name="$f")
    [[ $f == /* ]] && { add "$(realpath -s -m "$f")" library; return; }
  done
  ERRORS+=("library -l$1: the compiler finds no lib$1.so or lib$1.a")
}
link_commands() {
  if [[ -n $NINJA ]]; then
    "$NINJA" -C "$BUILD" -t commands | grep '^: ' || true
  else
    find "$BUILD" -name link.txt -exec cat {} +
  fi
}
declare -A LIBS=()
while read -ra words; do
  prev='&&'
  for t in "${words[@]}"; do
    case $t in
      -l*) LIBS[${t#-l}]=1 ;;
      /*.so | /*.so.* | /*.a) [[ $t == "$SRC"/* || $t == "$BUILD"/* ]] || add "$t" library ;;
      /*) [[ $prev == '&&' ]] && add "$t" tool ;;
    esac
    prev=$t
  done
done < <(link_commands)
IMPLICIT=$(find "$BUILD/CMakeFiles" -maxdepth 2 -name CMakeCXXCompiler.cmake -exec sed -n \
  's/^set(CMAKE_CXX_IMPLICIT_LINK_LIBRARIES "\(.*\)")/\1/p' {} +)
for n in ${IMPLICIT//;/ }; do LIBS[$n]=1; done
for n in "${!LIBS[@]}"; do add_libname "$n"; done

# Shared libraries the built executables load.
while read -r exe; do
  while read -r line; do
    case $line in
      *"=> not found"*) ERRORS+=("$exe needs ${line%% *}, which is not installed") ;;
      *"=> /"*) p=${line#*=> }; add "${p%% (*}" "loaded library" ;;
    esac
  done < <(ldd "$exe" 2>/dev/null || true)
done < <(find "$BUILD" -type f -perm -u+x ! -name '*.so*' ! -path '*/CompilerId*')

# Tools from CMakeCache.txt, and the run-time files.
for v in CMAKE_COMMAND CMAKE_CTEST_COMMAND CMAKE_CXX_COMPILER CMAKE_MAKE_PROGRAM PKG_CONFIG_EXECUTABLE; do
  p=$(cache "$v")
  [[ -n $p ]] && add "$p" tool
done
for r in "${RUNTIME[@]}"; do
  what=${r%%|*} why=${r#*|} p=
  case $what in
    exe:*) p=$(command -v "${what#exe:}" || true) ;;
    lib:*) p=$(/sbin/ldconfig -p | awk -v n="${what#lib:}" '$1 == n { print $NF; exit }') ;;
    *) [[ -e $what ]] && p=$what ;;
  esac
  if [[ -n $p ]]; then add "$p" "run-time file" "$why"; else ERRORS+=("${what#*:} not found ($why)"); fi
done

# Owners: dpkg -S on each path and on its real path (a symlink and its
# target may come from two packages: libz.so from zlib1g-dev, libz.so.1.2.13
# from zlib1g; both must be installed), each also in its /lib form (Debian
# 12's dpkg database still has /lib, /bin, /sbin for usrmerged files).
declare -A SELF=() REALF=() OWNER=()
FILES=("${!WHY[@]}")
mapfile -t REAL < <(realpath -m -- "${FILES[@]}")
# forms PATH: PATH and its /lib form, in $FORMS (no subshell: 4 000 forks took 10 s)
forms() { if [[ $1 =~ ^/usr/(lib|lib64|bin|sbin)/ ]]; then FORMS="$1 ${1#/usr}"; else FORMS=$1; fi; }
for i in "${!FILES[@]}"; do
  f=${FILES[i]} r=${REAL[i]}
  forms "$f"
  SELF[$f]=$FORMS
  [[ $r == "$f" ]] || { forms "$r"; REALF[$f]=$FORMS; }
done
while IFS= read -r line; do
  [[ $line == diversion* || $line != *": /"* ]] && continue
  pk=${line%%: /*} path=/${line#*: /}
  OWNER[$path]+=" ${pk//,/ }"
done < <(printf "%s\n" "${SELF[@]}" "${REALF[@]}" | tr ' ' '\n' | sort -u | xargs -d '\n' dpkg -S 2>/dev/null || true)

# The installed packages: Depends/Pre-Depends, Provides and the base set.
declare -A DEPS=() PROV=() PULLED=() BASE=()
base_seed=()
while IFS='#' read -r st name ess prio pre dep prov; do
  [[ $st == ii* ]] || continue
  DEPS[$name]="$pre${pre:+, }$dep"
  IFS=',' read -ra provs <<<"$prov"
  for v in "${provs[@]}"; do
    v=${v%%(*} v=${v//[[:space:]]/} v=${v%%:*}
    [[ -n $v ]] && PROV[$v]+=" $name"
  done
  [[ $ess == yes || $prio == required || $prio == important ]] && base_seed+=("$name")
done < <(dpkg-query -W -f='${db:Status-Abbrev}#${Package}#${Essential}#${Priority}#${Pre-Depends}#${Depends}#${Provides}\n')

# closure SET PACKAGE...: PACKAGE and what it depends on, recursively.
closure() {
  local -n out=$1
  shift
  local -a todo=("$@") groups alts
  local p g a n
  while ((${#todo[@]})); do
    p=${todo[-1]}
    unset 'todo[-1]'
    [[ -n ${out[$p]:-} ]] && continue
    out[$p]=1
    IFS=',' read -ra groups <<<"${DEPS[$p]:-}"
    for g in "${groups[@]}"; do
      IFS='|' read -ra alts <<<"$g"
      for a in "${alts[@]}"; do
        n=${a%%(*} n=${n//[[:space:]]/} n=${n%%:*}
        [[ -n $n ]] || continue
        if [[ -n ${DEPS[$n]+x} ]]; then todo+=("$n"); break; fi
        if [[ -n ${PROV[$n]:-} ]]; then todo+=(${PROV[$n]}); break; fi
      done
    done
  done
}
mapfile -t PACKAGES < <(bash "$SETUP" packages)
((${#PACKAGES[@]})) || die "$SETUP packages printed no packages"
KEPT=()
for p in "${PACKAGES[@]}"; do [[ -n ${DROP[$p]:-} ]] || KEPT+=("$p"); done
for p in "${KEPT[@]}"; do
  [[ -n ${DEPS[$p]+x} ]] || printf 'check_packages: note: %s is listed but not installed here\n' "$p"
done
closure PULLED "${KEPT[@]}"
closure BASE "${base_seed[@]}"

# The verdict, one line per file not covered.
declare -A USED=() MISSING=() BY_INDEX=()
# covered FILE PATH...: true if a package owning one of PATH is covered.
covered() {
  local f=$1 c o
  shift
  local -a owners=()
  for c in "$@"; do owners+=(${OWNER[$c]:-}); done
  for o in "${owners[@]}"; do
    USED[${o%%:*}]=1
    [[ -n ${PULLED[${o%%:*}]:-}${BASE[${o%%:*}]:-} ]] && return 0
  done
  o=${owners[0]%%:*}
  MISSING[$o]=1
  [[ ${WHY[$f]} == header ]] && BY_INDEX[$f]=${#ERRORS[@]}
  ERRORS+=("${WHY[$f]} $1${NOTE[$f]:+ (${NOTE[$f]})} is from package $o, which setup.sh does not install")
}
# used_by: each uncovered header's error names an object that includes it,
# from the OBJECT<TAB>HEADER pairs (one grep -r each took 20 s for a
# hundred headers).
used_by() {
  ((${#BY_INDEX[@]})) || return 0
  local h obj
  while IFS=$'\t' read -r h obj; do
    ERRORS[${BY_INDEX[$h]}]+=" (used by ${obj#"$BUILD"/})"
  done < <(awk -F '\t' '
    FNR == NR { want[$1] = $2; next }
    ($2 in want) && !($2 in seen) { seen[$2] = 1; print want[$2] "\t" $1 }' \
    <(for h in "${!BY_INDEX[@]}"; do printf '%s\t%s\n' "${RAW[$h]:-$h}" "$h"; done) "$PAIRS")
}
owned() { local c; for c in "$@"; do [[ -n ${OWNER[$c]:-} ]] && return 0; done; return 1; }
for f in $(printf '%s\n' "${!WHY[@]}" | sort); do
  read -ra self <<<"${SELF[$f]}"
  read -ra real <<<"${REALF[$f]:-}"
  if owned "${self[@]}"; then covered "$f" "${self[@]}" || true
  elif ((${#real[@]} == 0)) || ! owned "${real[@]}"; then
    ERRORS+=("${WHY[$f]} $f${NOTE[$f]:+ (${NOTE[$f]})} belongs to no Debian package")
    continue
  fi
  ((${#real[@]} == 0)) || ! owned "${real[@]}" || covered "$f" "${real[@]}" || true
done
used_by

n_lib=0 n_other=0
for f in "${!WHY[@]}"; do
  case ${WHY[$f]} in header) ;; *library) n_lib=$((n_lib + 1)) ;; *) n_other=$((n_other + 1)) ;; esac
done
summary="$NHEADERS system headers, $n_lib libraries, $n_other tools and run-time files, from ${#USED[@]} packages"
if ((${#ERRORS[@]})); then
  printf 'check_packages: ERROR: %s\n' "${ERRORS[@]}" >&2
  printf 'check_packages: FAIL: %s; not covered by setup.sh (%d packages, %d with their Depends) or the base: %s\n' \
    "$summary" "${#KEPT[@]}" "${#PULLED[@]}" "$(printf '%s\n' "${!MISSING[@]}" | sort | tr '\n' ' ')" >&2
  exit 1
fi
printf 'check_packages: OK: %s, all covered by setup.sh (%d packages, %d with their Depends) or the Debian 12 base (%d)\n' \
  "$summary" "${#KEPT[@]}" "${#PULLED[@]}" "${#BASE[@]}"
