#!/usr/bin/env bash
# Every error a user can cause is typed (solver/common/errors.h): the
# sources throw UsageError, SceneError, ReadError, IoError, DeviceError,
# RenderError, RunawayError, or a standard exception that names a fault of
# the program (std::logic_error, std::out_of_range) or a broken
# precondition of a library function (std::invalid_argument, rethrown by
# the readers as SceneError). The generic std::runtime_error would reach
# main as an "internal error" whatever its cause, so it is not thrown.
# Also checks that main maps each typed error to its documented status.
#   tests/layout/check_errors.sh [REPO_ROOT]
set -euo pipefail
cd "${1:-$(dirname "$0")/../..}"
bad=0
while IFS= read -r hit; do
  echo "$hit: throws the generic std::runtime_error; throw a typed error (solver/common/errors.h)"
  bad=1
done < <(grep -rn --include='*.h' --include='*.cpp' --include='*.in' \
           -E 'throw +std::(runtime_error|exception)\b' solver render app || true)
# main's catch clauses: each typed error before std::exception, with its status.
main=app/cli/main.cpp
expect=("InputError=2" "ReadError=2" "RunawayError=4" "IoError=5" "DeviceError=3" "RenderError=3" "std::exception=70")
for pair in "${expect[@]}"; do
  type=${pair%%=*} status=${pair##*=}
  block=$(grep -A6 -E "catch \(const [a-z:]*${type}& e\)" "$main" || true)
  if [[ -z $block ]]; then echo "$main: no catch clause for $type"; bad=1; continue; fi
  first_return=$(grep -oE "return [0-9]+;" <<<"$block" | head -1)
  [[ $first_return == "return ${status};" ]] || { echo "$main: $type does not return $status"; bad=1; }
done
# std::exception must be the last clause, after every typed one.
last=$(grep -oE 'catch \(const [A-Za-z:]+&' "$main" | tail -1)
[[ $last == "catch (const std::exception&" ]] || { echo "$main: the last catch is '$last', not std::exception"; bad=1; }
[[ $bad == 0 ]] && echo "check_errors: no generic runtime_error thrown; main's statuses as documented"
exit $bad
