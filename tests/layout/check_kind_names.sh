#!/usr/bin/env bash
# Where the apparatus kinds are named. A kind (ShearBox / shear_box, the
# names of solver/scene/apparatus/kinds.h's variant) is named in code only
#   - in its own folders and files: any source whose path names the kind
#     (solver/apparatus/shear_box/, solver/scene/apparatus/shear_box.h,
#     solver/io/scene_tables_shear_box.cpp, app/experiment/shear_box/,
#     app/lab/shear_box/, app/cli/campaign/shear_box_campaign.cpp), and
#     there no other kind is named;
#   - in the tables that list the kinds, one per layer (kTables below:
#     the solver's registry, the scene's variant and table readers, and the
#     front ends' tables of reports, built-in scenes, lab benches and
#     campaigns).
# Comments, string literals (messages, TOML keys) and #include lines are
# not code and are not searched. Prints each offending line.
#   tests/layout/check_kind_names.sh [REPO_ROOT]
set -euo pipefail
cd "${1:-$(dirname "$0")/../..}"
types=$(grep -oE 'std::variant<std::monostate(, [A-Za-z]+)+>' solver/scene/apparatus/kinds.h |
        sed -E 's/std::variant<std::monostate, //; s/>//; s/, / /g')
[[ -n $types ]] || { echo "check_kind_names: no Apparatus variant in solver/scene/apparatus/kinds.h"; exit 1; }
kTables=" solver/apparatus/registry.h solver/apparatus/registry.cpp solver/scene/apparatus/kinds.h
  solver/io/scene_tables.h solver/io/scene_tables_apparatus.cpp
  app/experiment/apparatus_report.h app/experiment/apparatus_report.cpp
  app/experiment/default_scenes.h app/experiment/default_scene.cpp.in
  app/lab/lab_apparatus.h app/lab/lab_apparatus.cpp
  app/cli/cmd_campaign.cpp app/cli/campaign/campaign_command.h "
snake() { sed -E 's/([a-z0-9])([A-Z])/\1_\2/g' <<<"$1" | tr '[:upper:]' '[:lower:]'; }
declare -A snake_of
for t in $types; do snake_of[$t]=$(snake "$t"); done
any=""  # every kind's names, to skip the files that name none
for t in $types; do any+="${any:+|}$t|${snake_of[$t]}"; done
bad=0 files=0
while IFS= read -r -d '' f; do  # the sources whose text names a kind at all
  files=$((files + 1))
  [[ " ${kTables//$'\n'/ } " == *" $f "* ]] && continue
  # the code only: no #include lines, // comments or string literals
  code=$(sed -E '/^[[:space:]]*#[[:space:]]*include/d; s/"([^"\\]|\\.)*"/""/g; s@//.*$@@' "$f")
  grep -qE "$any" <<<"$code" || continue
  own=""
  for t in $types; do [[ $f == *"${snake_of[$t]}"* ]] && own=$t; done
  for t in $types; do
    [[ $t == "$own" ]] && continue
    s=${snake_of[$t]}
    hits=$(grep -nE "(^|[^A-Za-z0-9])($t|$s)([^a-z0-9]|$)|(^|[^A-Za-z0-9_])${t}[A-Z][a-z]" <<<"$code" || true)
    if [[ -n $hits ]]; then
      while IFS= read -r h; do echo "$f:${h%%:*}: names the apparatus kind $t outside its folders:${h#*:}"; done <<<"$hits"
      bad=1
    fi
  done
done < <(find solver render app \( -name '*.h' -o -name '*.cpp' -o -name '*.in' -o -name '*.cl' \) -print0 |
           xargs -0 grep -lZE "$any" || true)
[[ $bad == 0 ]] && echo "check_kind_names: $files sources name a kind; the kinds ($types) are named only in their folders and the kinds' tables"
exit $bad
