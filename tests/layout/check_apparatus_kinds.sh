#!/usr/bin/env bash
# The registry (solver/apparatus/registry.h) is the only place that tells
# apparatus kinds apart. Outside solver/apparatus/ and the scene's table
# readers and writer, a source may use one kind on purpose (the paper's
# programme is a shear-box campaign, the triaxial campaign a triaxial one,
# each lab bench its own kind), but no source tests a scene for two kinds
# or more: that is an if-chain over kinds, which belongs in a table keyed by
# the registry's names (ApparatusKind, entry_for_kind). Nor does any source
# inspect the Apparatus variant's alternatives directly.
#   tests/layout/check_apparatus_kinds.sh [REPO_ROOT]
set -euo pipefail
cd "${1:-$(dirname "$0")/../..}"
kinds=$(grep -oE 'std::variant<std::monostate(, [A-Za-z]+)+>' solver/scene/apparatus/kinds.h |
        sed -E 's/std::variant<std::monostate, //; s/>//; s/, / /g')
[[ -n $kinds ]] || { echo "check_apparatus_kinds: no Apparatus variant in solver/scene/apparatus/kinds.h"; exit 1; }
bad=0 files=0
while IFS= read -r -d '' f; do
  case $f in
    solver/apparatus/*|solver/io/scene_tables_*|solver/io/scene_writer.cpp|solver/scene/*) continue ;;
  esac
  files=$((files + 1))  # the sources that name an alternative or cast to one
  tested=""
  for k in $kinds; do
    if grep -qE "(if \(|\? |&& |\|\| |!|return )[^;]*apparatus_as<$k>|apparatus_as<$k>\(\) *(\?|&&|\|\|)" "$f"; then
      tested+=" $k"
    fi
  done
  if [[ $(wc -w <<<"$tested") -gt 1 ]]; then
    echo "$f: tests the scene for several apparatus kinds ($tested ); ask the registry (solver/apparatus/registry.h)"
    bad=1
  fi
  if grep -nE "holds_alternative<($(tr ' ' '|' <<<"$kinds"))>|\.apparatus\.index\(\)" "$f"; then
    echo "$f: inspects Scene::apparatus's alternatives; ask the registry (apparatus_kind)"
    bad=1
  fi
done < <(find solver render app \( -name '*.h' -o -name '*.cpp' -o -name '*.in' \) -print0 |
           xargs -0 grep -lZE 'apparatus_as<|holds_alternative<|\.apparatus\.index\(' || true)
[[ $bad == 0 ]] && echo "check_apparatus_kinds: the $files sources outside the apparatus folders that cast to a kind test at most one ($kinds)"
exit $bad
