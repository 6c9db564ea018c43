#!/usr/bin/env bash
# The docs name files that exist: every `folder/file` quoted in docs/*.md,
# README.md and the folders' READMEs is a path of the repository (from its
# root, from the quoting file's folder or from that folder's parent), so
# the architecture's recipes and the READMEs' tables cannot name a file
# that was moved or removed. Paths of what a run writes (results/,
# build/, a run's own folders) are not checked: they start elsewhere. And
# tests/ mirrors the source folders, as docs/architecture.md says.
#   tests/layout/check_doc_paths.sh [REPO_ROOT]
set -euo pipefail
cd "${1:-$(dirname "$0")/../..}"
roots='^(solver|app|render|tests|docs|assets|shaders|\.ci)/'
bad=0 checked=0
while IFS= read -r -d '' f; do
  dir=$(dirname "$f")
  while IFS= read -r p; do
    case $p in *'<'*|*'*'*|*'…'*) continue ;; esac
    # relative to the quoting file's folder (or its parent) only in READMEs
    [[ $p =~ $roots || ($(basename "$f") == README.md && $dir != .) ]] || continue
    checked=$((checked + 1))
    [[ -e $p || -e $dir/$p || -e $dir/../$p ]] && continue
    echo "$f: names $p, which does not exist"
    bad=1
  done < <(grep -oE '`[A-Za-z0-9_.-]+/[A-Za-z0-9_./-]+`' "$f" | tr -d '`' | sed -E 's/[.,:;]+$//' | sort -u)
done < <(find docs solver app render tests assets shaders -name '*.md' -print0; printf '%s\0' README.md)
# docs/architecture.md: "tests/ mirrors the source folders".
while IFS= read -r d; do
  src=${d#tests/}
  [[ -d $src ]] || { echo "$d: mirrors no source folder ($src does not exist; docs/architecture.md)"; bad=1; }
done < <(find tests/solver tests/app tests/render -type d)
[[ $bad == 0 ]] && echo "check_doc_paths: $checked paths named in the docs exist; tests/ mirrors the sources"
exit $bad
