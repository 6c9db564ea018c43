#!/usr/bin/env bash
# The README's promise on a fresh Debian 12 machine, for real: builds a clean
# bookworm root with mmdebstrap (default variant: the required and important
# packages, plus sudo), clones the repository at COMMIT into it, and there,
# as a new user with sudo, runs `./setup.sh` then `./setup.sh test`.
# Everything goes to a log; a summary is printed at the end. Run as root.
#
# Usage: sudo tests/fresh-root.sh [COMMIT]      (default: HEAD)
# Environment:
#   MIRROR    Debian mirror (default http://deb.debian.org/debian)
#   WORKDIR   where the root and the log go (default: a new /var/tmp/simsols-fresh-root.*)
#   KEEP=1    keep the root afterwards (it is removed by default; the log stays)
#   FIRST_RUN_ONLY=1   stop after `./setup.sh` (the minutes to the default
#             experiment's results), without `./setup.sh test`
set -euo pipefail

die() { printf 'fresh-root: %s\n' "$*" >&2; exit 2; }
((EUID == 0)) || die "run as root (it makes a chroot)"
REPO=$(git -C "$(dirname "${BASH_SOURCE[0]}")" rev-parse --show-toplevel)
SHA=$(git -C "$REPO" rev-parse --verify "${1:-HEAD}^{commit}") || die "no commit ${1:-HEAD}"
MIRROR=${MIRROR:-http://deb.debian.org/debian}
WORKDIR=${WORKDIR:-$(mktemp -d /var/tmp/simsols-fresh-root.XXXXXX)}
ROOT=$WORKDIR/root
LOG=$WORKDIR/fresh-root.log
USER_NAME=lab
mkdir -p "$WORKDIR"
: >"$LOG"
t0=$SECONDS

say() { printf '==> %s\n' "$*" | tee -a "$LOG"; }
# Runs a command, its output into the log with the seconds since the start.
logged() {
  "$@" 2>&1 | while IFS= read -r l; do printf '[%5ds] %s\n' $((SECONDS - t0)) "$l"; done >>"$LOG"
  return "${PIPESTATUS[0]}"
}

cleanup() {
  local m p
  # processes a failed test left running inside the root (an Xvfb, say)
  # would keep its mounts busy
  for p in /proc/[0-9]*; do
    [[ $(readlink "$p/root" 2>/dev/null) == "$ROOT" ]] && kill "${p#/proc/}" 2>/dev/null
  done
  sleep 1
  for m in dev sys proc; do
    mountpoint -q "$ROOT/$m" 2>/dev/null && { umount -R "$ROOT/$m" || umount -R -l "$ROOT/$m"; }
  done
  if [[ -z ${KEEP:-} && -d $ROOT ]]; then
    if findmnt -rno TARGET | grep -q "^$ROOT/"; then
      echo "fresh-root: something is still mounted under $ROOT; not removing it" >&2
    else
      rm -rf --one-file-system "$ROOT"
    fi
  fi
}
trap cleanup EXIT

command -v mmdebstrap >/dev/null || {
  say "Installing mmdebstrap"
  logged apt-get install -y --no-install-recommends mmdebstrap
}

say "Commit $SHA ($(git -C "$REPO" log -1 --format=%s "$SHA" | cut -c1-60)); log: $LOG"
git -C "$REPO" diff --quiet HEAD || say "note: uncommitted changes in $REPO are not part of the test"
say "Making a Debian 12 root in $ROOT from $MIRROR"
start=$SECONDS
logged mmdebstrap --variant=debootstrap --include=sudo bookworm "$ROOT" \
  "deb $MIRROR bookworm main" "deb $MIRROR bookworm-updates main" \
  "deb ${MIRROR%/debian}/debian-security bookworm-security main" || die "mmdebstrap failed (see $LOG)"
t_root=$((SECONDS - start))
base_count=$(chroot "$ROOT" dpkg-query -W -f='${db:Status-Abbrev}\n' | grep -c '^ii')

say "Cloning the repository into it, as user $USER_NAME (with sudo)"
chroot "$ROOT" useradd -m -s /bin/bash "$USER_NAME"
echo "$USER_NAME ALL=(ALL) NOPASSWD: ALL" >"$ROOT/etc/sudoers.d/$USER_NAME"
HOME_DIR=$ROOT/home/$USER_NAME
git clone -q --no-hardlinks --no-checkout "$REPO" "$HOME_DIR/simsols"
git -C "$HOME_DIR/simsols" -c advice.detachedHead=false checkout -q "$SHA"
chroot "$ROOT" chown -R "$USER_NAME:" "/home/$USER_NAME"

mount -t proc proc "$ROOT/proc"
for m in sys dev; do mount --rbind "/$m" "$ROOT/$m" && mount --make-rslave "$ROOT/$m"; done

as_user() { logged chroot "$ROOT" runuser -l "$USER_NAME" -c "cd simsols && $1"; }
status=0
say "Running ./setup.sh"
start=$SECONDS
as_user ./setup.sh && run_rc=0 || run_rc=$?
t_run=$((SECONDS - start))
test_rc=0 t_test=0
if [[ -z ${FIRST_RUN_ONLY:-} ]]; then
  say "Running ./setup.sh test"
  start=$SECONDS
  as_user "./setup.sh test" && test_rc=0 || test_rc=$?
  t_test=$((SECONDS - start))
fi
((run_rc == 0 && test_rc == 0)) || status=1

# Summary, from the log.
phase() { grep -m1 -n "$1" "$LOG" | sed 's/^\([0-9]*\):\[ *\([0-9]*\)s\].*/\2/' || true; }
b0=$(phase '==> Building ') b1=$(phase '==> Running the default experiment')
installed=$(sed -n 's/.*==> Installing missing packages: //p' "$LOG" | head -n 1)
{
  echo
  echo "fresh-root summary ($(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores $(uname -m), commit ${SHA:0:12})"
  echo "  root: $base_count packages (mmdebstrap bookworm, variant debootstrap, + sudo), made in ${t_root} s"
  echo "  setup.sh installed $(wc -w <<<"$installed") packages: $installed"
  grep -o '[0-9]* newly installed' "$LOG" | sort -n | tail -n 1 | sed 's/^/  apt: /' || true
  [[ -n $b0 && -n $b1 ]] && echo "  build: $((b1 - b0)) s"
  echo "  ./setup.sh: exit $run_rc in ${t_run} s (from the clone to the default experiment's results)"
  [[ -z ${FIRST_RUN_ONLY:-} ]] && echo "  ./setup.sh test: exit $test_rc in ${t_test} s"
  grep -E 'shear test finished|phi_peak|phi_residual|largest  tau' "$LOG" | sed 's/^\[ *[0-9]*s\] /  /' || true
  grep -E 'tests passed,|Total Test time' "$LOG" | sed 's/^\[ *[0-9]*s\] /  /' || true
  sed -n '/The following tests FAILED/,/Errors while running/p' "$LOG" | sed 's/^\[ *[0-9]*s\] /  /'
  echo "  result: $([[ $status == 0 ]] && echo PASS || echo FAIL); log: $LOG"
} | tee -a "$LOG"
exit "$status"
