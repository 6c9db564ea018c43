#!/usr/bin/env bash
# The folders' dependency rules (solver/README.md, render/README.md,
# app/README.md): each source folder (with its subfolders, such as
# solver/apparatus/shear_box) may include only the folders listed for it.
# Prints every include that breaks a rule and fails if there is one.
#   tests/layout/check_layers.sh [REPO_ROOT]
set -euo pipefail
cd "${1:-$(dirname "$0")/../..}"
declare -A allowed=(
  [solver/common]=""
  [solver/scene]="solver/common"
  [solver/kernels]=""
  [solver/core]="solver/common solver/scene solver/kernels"
  [solver/apparatus]="solver/common solver/scene solver/core"
  [solver/io]="solver/common solver/scene solver/core solver/apparatus"
  [render/plot]="solver/common"
  [render/gl]="render/plot solver/common"
  [render/view]="render/plot render/gl solver/common solver/kernels solver/core"
  [app/experiment]="render/plot solver/common solver/scene solver/core solver/apparatus solver/io"
  [app/lab]="app/experiment render/plot render/gl render/view solver/common solver/scene solver/core solver/apparatus solver/io"
  [app/cli]="app/experiment app/lab render/plot render/gl render/view solver/common solver/scene solver/core solver/apparatus solver/io"
  [app/python]="app/experiment solver/common solver/scene solver/core solver/apparatus solver/io"
)
bad=0 checked=0
for dir in "${!allowed[@]}"; do
  [[ -d $dir ]] || { echo "check_layers: $dir is missing" >&2; bad=1; continue; }
  while IFS=: read -r file line text; do
    [[ $text =~ \#include\ \"([a-z_]+/[a-z_]+)/ ]] || continue
    target=${BASH_REMATCH[1]}
    checked=$((checked + 1))
    [[ $target == "$dir" ]] && continue
    if [[ " ${allowed[$dir]} " != *" $target "* ]]; then
      echo "$file:$line: $dir may not include $target (${text#*#})"
      bad=1
    fi
  done < <(find "$dir" \( -name '*.h' -o -name '*.cpp' -o -name '*.in' \) -print0 |
             xargs -0 -r grep -Hn '#include "[a-z_]*/[a-z_]*/' 2>/dev/null || true)
done
# Every source folder is under a rule.
for dir in $(find solver render app -mindepth 1 -maxdepth 1 -type d | sort); do
  [[ -v "allowed[$dir]" ]] || { echo "check_layers: $dir has no rule in $0"; bad=1; }
done
echo "check_layers: $checked includes checked in ${#allowed[@]} folders"
exit $bad
