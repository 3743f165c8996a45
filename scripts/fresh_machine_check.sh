#!/usr/bin/env bash
# The README's set-up on a machine that has nothing yet, on demand (not in CI):
#   scripts/fresh_machine_check.sh [--dir DIR] [--keep]
# Builds an empty Debian 12 (bookworm) root with debootstrap from the Debian mirror apt already
# uses here (read from /etc/apt/sources.list*; the root gets the same bookworm, -updates and
# -security sources), clones this repository's HEAD into /root/impulse2d there and runs, as root
# in a chroot with a clean environment and no display:
#   1. scripts/demo.sh, as the README says: it installs, builds and launches the demo (without
#      RViz, as there is no display); proven started when /impulse2d/get_body_state is advertised
#      on its master (a free port), then stopped with Ctrl-C's SIGINT;
#   2. scripts/test.sh: everything CI runs;
#   3. the examples stage (scripts/test.d/70-examples.sh) once more on its own;
# and prints how long each took. Needs root (debootstrap, chroot, mount) and installs debootstrap
# when it is missing. DIR (default /var/tmp/impulse2d_fresh) holds the root (DIR/root, removed
# first when there from an earlier run, and at the end unless --keep) and the logs (DIR/logs,
# summary.txt the last lines printed). /proc, /sys, /dev/pts and /dev/shm are mounted into the root
# for the run and unmounted afterwards, also on failure or Ctrl-C. Takes about 20 minutes on a
# 2-core VM (measured 2026-11-23).
# Exit status: 0 when all three passed, 1 when one failed, 2 when the check could not run.
# The whole script is one function, read before it runs: editing the file meanwhile is safe.
main() {
  set -uo pipefail
  REPO="$(cd "$(dirname "$0")/.." && pwd)"
  export PATH="/usr/bin:/usr/sbin:/bin:/sbin:$PATH"
  DIR=/var/tmp/impulse2d_fresh
  KEEP=0
  DEMO_TIMEOUT=5400  # s for the first scripts/demo.sh: it installs every package and builds
  TEST_TIMEOUT=7200  # s for scripts/test.sh
  EXAMPLES_TIMEOUT=1500

  die() { echo "fresh_machine_check.sh: $*" >&2; exit 2; }
  while [ $# -gt 0 ]; do
    case "$1" in
      --dir) [ $# -ge 2 ] || die "--dir needs a folder"; DIR="$2"; shift 2 ;;
      --keep) KEEP=1; shift ;;
      -h | --help) sed -n '2,3p' "$0" | sed 's/^# *//'; exit 0 ;;
      *) die "unknown argument $1 (see --help)" ;;
    esac
  done
  [ "$(id -u)" -eq 0 ] || die "needs root (debootstrap, chroot and mount)"
  DIR="$(realpath -m "$DIR")"
  case "$DIR/" in "$REPO/"*) die "--dir must be outside the repository" ;; esac
  mkdir -p "$DIR" || die "cannot make $DIR"
  ROOT="$DIR/root"
  LOGS="$DIR/logs"

  # --- the root, and taking it down again ------------------------------------------------------
  mounted=()  # mount points inside ROOT, unmounted in reverse order
  chroot_processes() {  # pids of processes whose root directory is ROOT (all started by this script)
    local p
    for p in /proc/[0-9]*; do
      [ "$(readlink "$p/root" 2>/dev/null)" = "$ROOT" ] && echo "${p#/proc/}"
    done
  }
  take_down() {
    set +e
    local pids i
    mapfile -t pids < <(chroot_processes)
    if [ ${#pids[@]} -gt 0 ]; then
      kill -INT "${pids[@]}" 2>/dev/null
      for i in $(seq 20); do
        mapfile -t pids < <(chroot_processes)
        [ ${#pids[@]} -eq 0 ] && break
        sleep 0.5
      done
      [ ${#pids[@]} -gt 0 ] && kill -KILL "${pids[@]}" 2>/dev/null && sleep 1
    fi
    for ((i = ${#mounted[@]} - 1; i >= 0; i--)); do
      umount "${mounted[i]}" 2>/dev/null || umount -l "${mounted[i]}"
    done
    mounted=()
  }
  remove_root() {  # only when nothing is mounted below it: rm must never reach the host's /proc or /dev
    [ -e "$ROOT" ] || return 0
    if findmnt -rn -o TARGET | grep -q "^$ROOT/"; then
      die "something is still mounted below $ROOT (findmnt); unmount it and run again"
    fi
    rm -rf --one-file-system "$ROOT"
  }
  trap 'take_down; [ "$KEEP" = 1 ] || remove_root' EXIT
  trap 'exit 130' INT TERM HUP

  mount_into_root() {  # mount_into_root TARGET MOUNT-ARGS...
    mkdir -p "$ROOT/$1"
    mount "${@:2}" "$ROOT/$1" || die "cannot mount $1 into the root"
    mounted+=("$ROOT/$1")
  }

  # The Debian mirror and the security mirror apt uses on this machine (one-line and deb822 files).
  read -r MIRROR SECURITY < <(python3 - <<'PY'
import glob, re
mirror = security = ""
entries = []
for path in ["/etc/apt/sources.list"] + sorted(glob.glob("/etc/apt/sources.list.d/*.list")):
    try:
        for line in open(path):
            m = re.match(r"\s*deb\s+(\[[^]]*\]\s+)?(\S+)\s+(\S+)", line)
            if m:
                entries.append((m.group(2), [m.group(3)]))
    except OSError:
        pass
for path in sorted(glob.glob("/etc/apt/sources.list.d/*.sources")):
    for stanza in re.split(r"\n\s*\n", open(path).read()):
        fields = dict(re.findall(r"^([A-Za-z-]+):\s*(.*)$", stanza, re.M))
        if "deb" in fields.get("Types", "").split() and fields.get("Enabled", "yes") != "no":
            for uri in fields.get("URIs", "").split():
                entries.append((uri, fields.get("Suites", "").split()))
for uri, suites in entries:
    if "bookworm" in suites and not mirror:
        mirror = uri
    if "bookworm-security" in suites and not security:
        security = uri
print(mirror or "-", security or "-")
PY
  )
  [ "$MIRROR" != "-" ] || die "no Debian 12 (bookworm) source in /etc/apt/sources.list*"

  if ! command -v debootstrap >/dev/null; then
    echo "fresh_machine_check.sh: installing debootstrap" >&2
    DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends debootstrap >&2 ||
      die "cannot install debootstrap"
  fi

  commit="$(git -C "$REPO" rev-parse HEAD)" || die "$REPO is not a git checkout"
  [ -z "$(git -C "$REPO" status --porcelain --untracked-files=no)" ] ||
    echo "fresh_machine_check.sh: uncommitted changes are not part of the check (it clones HEAD)" >&2
  remove_root
  rm -rf "$LOGS"
  mkdir -p "$LOGS"
  summary=()
  say() { echo "$*"; summary+=("$*"); }
  minutes() { awk -v s="$1" 'BEGIN { printf "%.1f", s / 60 }'; }
  say "fresh machine check of $commit, $(date -u '+%Y-%m-%d %H:%M UTC'), Debian 12 from $MIRROR"

  started=$SECONDS
  debootstrap bookworm "$ROOT" "$MIRROR" >"$LOGS/debootstrap.log" 2>&1 ||
    { tail -n 20 "$LOGS/debootstrap.log" >&2; die "debootstrap failed (log: $LOGS/debootstrap.log)"; }
  say "debootstrap (the empty root): $(minutes $((SECONDS - started))) min"

  {
    echo "Types: deb"
    echo "URIs: $MIRROR"
    echo "Suites: bookworm bookworm-updates"
    echo "Components: main"
    if [ "$SECURITY" != "-" ]; then
      echo
      echo "Types: deb"
      echo "URIs: $SECURITY"
      echo "Suites: bookworm-security"
      echo "Components: main"
    fi
  } >"$ROOT/etc/apt/sources.list.d/debian.sources"
  rm -f "$ROOT/etc/apt/sources.list"
  # The machine's name must resolve there as on any installed machine (ROS nodes advertise it).
  cp /etc/resolv.conf /etc/hosts "$ROOT/etc/"
  # As in every chroot: packages do not start daemons, which would outlive the run.
  printf '#!/bin/sh\nexit 101\n' >"$ROOT/usr/sbin/policy-rc.d"
  chmod +x "$ROOT/usr/sbin/policy-rc.d"
  git clone --quiet --no-local "$REPO" "$ROOT/root/impulse2d" || die "cannot clone $REPO"
  git -C "$ROOT/root/impulse2d" checkout --quiet "$commit" || die "cannot check out $commit"

  mount_into_root proc -t proc proc
  mount_into_root sys -t sysfs sysfs
  mount_into_root dev/pts --bind /dev/pts
  mount_into_root dev/shm -t tmpfs -o mode=1777 tmpfs
  [ -c "$ROOT/dev/null" ] || die "debootstrap made no /dev/null in the root"

  in_root() {  # in_root LOG TIMEOUT SCRIPT: runs SCRIPT with bash in the root, as a fresh login would
    timeout -k 30 "$2" chroot "$ROOT" /usr/bin/env -i HOME=/root LANG=C.UTF-8 TERM=dumb \
      PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
      bash -c "cd /root/impulse2d && $3" >"$1" 2>&1
  }
  failed=0
  step_result() {  # step_result NAME STATUS START LOG
    local verdict=pass
    [ "$2" -eq 0 ] || { verdict="FAILED (exit $2; log: $4)"; failed=1; tail -n 25 "$4" >&2; }
    say "$1: $(minutes $((SECONDS - $3))) min, $verdict"
  }

  # 1. scripts/demo.sh until the world answers on a master of its own, then Ctrl-C.
  port="$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')"
  started=$SECONDS
  in_root "$LOGS/demo.log" "$DEMO_TIMEOUT" "
    export ROS_MASTER_URI=http://127.0.0.1:$port  # a free port: never another roscore of this machine
    set -m  # the demo in a process group of its own, where SIGINT reaches it as Ctrl-C would
    scripts/demo.sh &
    demo=\$!
    stop_demo() {
      kill -INT -- -\$demo 2>/dev/null
      for i in \$(seq 40); do kill -0 \$demo 2>/dev/null || return 0; sleep 0.5; done
      echo 'scripts/demo.sh did not stop within 20 s of SIGINT'
      kill -KILL -- -\$demo
      return 1
    }
    trap stop_demo EXIT
    trap 'exit 143' TERM
    until command -v rosservice >/dev/null && rosservice list 2>/dev/null | grep -qx /impulse2d/get_body_state; do
      kill -0 \$demo 2>/dev/null || { echo 'scripts/demo.sh ended before the world came up'; exit 1; }
      sleep 2
    done
    source \${IMPULSE2D_WS:-~/.cache/impulse2d_ws}/devel/setup.bash  # impulse2d's types
    answer=\"\$(rosservice call /impulse2d/get_body_state ground)\"
    echo \"=== the demo's world on \$ROS_MASTER_URI answers: \$(echo \"\$answer\" | head -n 3 | tr '\n' ' ')\"
    trap - EXIT
    stop_demo || exit 1
    echo \"\$answer\" | grep -qx 'success: True'"
  step_result "scripts/demo.sh (installs, builds, the demo starts)" $? "$started" "$LOGS/demo.log"

  # 2. scripts/test.sh, as written in the README (its own workspace, built from scratch).
  started=$SECONDS
  in_root "$LOGS/test.log" "$TEST_TIMEOUT" "scripts/test.sh"
  status=$?
  step_result "scripts/test.sh ($(tail -n 1 "$LOGS/test.log"))" "$status" "$started" "$LOGS/test.log"

  # 3. The examples stage on its own, in the workspace test.sh built.
  started=$SECONDS
  in_root "$LOGS/examples.log" "$EXAMPLES_TIMEOUT" "REPO=/root/impulse2d \
    IMPULSE2D_WS=/root/.cache/impulse2d_ws STAGE_RESULTS=/root/examples_results \
    bash scripts/test.d/70-examples.sh"
  status=$?
  step_result "examples stage ($(grep '^examples:' "$LOGS/examples.log" | tail -n 1))" "$status" \
    "$started" "$LOGS/examples.log"

  say "fresh machine check: $([ "$failed" -eq 0 ] && echo PASSED || echo FAILED)"
  printf '%s\n' "${summary[@]}" >"$LOGS/summary.txt"
  exit "$failed"
}

main "$@"
