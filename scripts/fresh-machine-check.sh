#!/usr/bin/env bash
# Proves the README's two commands on a new Debian 12 machine: builds a minimal root with
# `debootstrap --variant=minbase` (plus git, sudo and CA certificates, nothing of deepvox's), clones
# this repository's HEAD into it and runs scripts/demo.sh then scripts/test.sh inside a chroot,
# first as a user with sudo (the packages are all missing, so scripts/install-deps.sh installs
# them through sudo), then as root from a second fresh clone. A third step simulates a configure
# that did not finish (generated build system removed, CMakeCache.txt kept) and runs the build
# again. Prints each command's wall time and exits non-zero when any command fails.
#
# Usage (as root, with Debian's mirror reachable):
#   scripts/fresh-machine-check.sh [ROOT_DIR]      # default ROOT_DIR: /var/tmp/deepvox-fresh-root
# Environment: DEEPVOX_FRESH_MIRROR (default http://deb.debian.org/debian), DEEPVOX_FRESH_AS
# ("user root" by default: which runs to make), DEEPVOX_FRESH_KEEP=1 keeps an existing root
# (its packages stay installed, so only a new root proves the install step).
# Only committed work is checked: the clone is of HEAD.
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
root=${1:-/var/tmp/deepvox-fresh-root}
mirror=${DEEPVOX_FRESH_MIRROR:-http://deb.debian.org/debian}
runs=${DEEPVOX_FRESH_AS:-user root}
log_dir="$root.logs"

if [ "$(id -u)" -ne 0 ]; then
  echo "fresh-machine-check: needs root (debootstrap and chroot)" >&2
  exit 2
fi
command -v debootstrap >/dev/null || {
  apt-get update -q && DEBIAN_FRONTEND=noninteractive apt-get install -y -q debootstrap
}

mounted=()
cleanup() {
  for ((i = ${#mounted[@]} - 1; i >= 0; i--)); do umount -l "${mounted[i]}" 2>/dev/null || true; done
}
trap cleanup EXIT
# --rbind: /sys with its submounts (cgroup2 under /sys/fs/cgroup, which slurmd needs).
bind() { mkdir -p "$root$1" && mount --rbind "$1" "$root$1" && mounted+=("$root$1"); }

mkdir -p "$log_dir"
summary="$log_dir/summary.txt"
: > "$summary"
note() { echo "$*" | tee -a "$summary"; }
timed() {  # timed LABEL LOGFILE COMMAND...: runs, logs, records wall seconds and exit status
  local label=$1 log=$2 start status
  shift 2
  start=$(date +%s)
  set +e
  "$@" > "$log" 2>&1
  status=$?
  set -e
  note "$label: exit $status, $(($(date +%s) - start)) s (log: $log)"
  return $status
}

if [ -d "$root" ] && [ "${DEEPVOX_FRESH_KEEP:-0}" != 1 ]; then
  rm -rf "$root"
fi
if [ ! -x "$root/bin/bash" ]; then
  timed "debootstrap minbase bookworm" "$log_dir/debootstrap.log" \
    debootstrap --variant=minbase --include=git,sudo,ca-certificates bookworm "$root" "$mirror"
fi
cat > "$root/etc/apt/sources.list" <<EOF
deb $mirror bookworm main
deb $mirror bookworm-updates main
deb ${mirror%/debian}/debian-security bookworm-security main
EOF
cp /etc/resolv.conf "$root/etc/resolv.conf"
bind /proc
bind /sys
bind /dev
bind /dev/pts
chroot "$root" bash -c 'id -u dev >/dev/null 2>&1 || useradd -m -s /bin/bash dev'
echo 'dev ALL=(ALL) NOPASSWD:ALL' > "$root/etc/sudoers.d/dev"
chmod 440 "$root/etc/sudoers.d/dev"
note "checked commit: $(git -C "$repo" rev-parse HEAD)$(git -C "$repo" diff --quiet HEAD || echo ' (uncommitted changes are not checked)')"
note "root: $root ($(chroot "$root" dpkg-query -W -f='.' | wc -c) packages before the commands)"

status=0
for who in $runs; do
  case $who in
    user) home=/home/dev spec=(--userspec=dev:dev) ;;
    root) home=/root spec=() ;;
    *) echo "fresh-machine-check: unknown run '$who' (user or root)" >&2; exit 2 ;;
  esac
  rm -rf "$root$home/deepvox"
  git clone -q --no-hardlinks "$repo" "$root$home/deepvox"
  chroot "$root" chown -R "$([ "$who" = user ] && echo dev:dev || echo root:root)" "$home/deepvox"
  run_in() {
    chroot "${spec[@]}" "$root" env -i HOME="$home" PATH=/usr/sbin:/usr/bin:/sbin:/bin \
      LANG=C.UTF-8 bash -c "cd $home/deepvox && $1"
  }
  timed "$who: scripts/demo.sh" "$log_dir/$who-demo.log" run_in "bash scripts/demo.sh" || status=1
  timed "$who: scripts/test.sh" "$log_dir/$who-test.log" run_in "bash scripts/test.sh" || status=1
  note "$who: $(grep -E 'tests passed|tests failed' "$log_dir/$who-test.log" | tail -n 1)"
done
# A configure that did not finish leaves CMakeCache.txt but no generated build system.
rm -f "$root$home/deepvox/build/Makefile" "$root$home/deepvox/build/build.ninja"
timed "$who: scripts/build.sh after an unfinished configure" "$log_dir/$who-rebuild.log" \
  run_in "bash scripts/build.sh --target deepvox" || status=1
note "fresh-machine-check: $([ $status -eq 0 ] && echo passed || echo FAILED)"
exit $status
