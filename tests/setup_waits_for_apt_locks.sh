#!/usr/bin/env bash
# scripts/setup waits while another apt or dpkg holds the package locks (scripts/apt_locks.sh):
# it failed at once ("Could not get lock /var/lib/dpkg/lock-frontend") on a fresh machine whose
# first automatic upgrade was running. Here a lock file of the test's own, held by flock(1).
# Usage: setup_waits_for_apt_locks.sh SOURCE_DIR
set -euo pipefail
source "$1/scripts/apt_locks.sh"
fail() { echo "setup_waits_for_apt_locks: $*" >&2; exit 1; }
[ -r /proc/locks ] || { echo "setup_waits_for_apt_locks: no /proc/locks here: skipped"; exit 0; }
work=$(mktemp -d)
waiter=""
cleanup() {
  if [ -n "$waiter" ]; then kill "$waiter" 2>/dev/null || true; fi
  rm -rf "$work"
}
trap cleanup EXIT
lock=$work/lock-frontend
: > "$lock"

# Free: no wait, no word.
out=$(wait_for_apt_locks 5 "$lock") || fail "a free lock was not taken as free"
[ -z "$out" ] || fail "a free lock said: $out"

# Held throughout (by this shell): the wait is said, and ends at its bound naming the lock.
exec 9> "$lock"
flock 9
lock_is_held "$lock" || fail "a lock held by flock is not seen in /proc/locks"
if out=$(wait_for_apt_locks 1 "$lock" 2>&1); then fail "a held lock was not waited for"; fi
grep -q "holds $lock .*waiting for it, at most 1 s" <<< "$out" || fail "no line saying it waits: $out"
grep -q "$lock is still held after 1 s" <<< "$out" || fail "no line naming the lock held: $out"

# Released while it waits: it goes on.
wait_for_apt_locks 600 "$lock" > "$work/out" 2>&1 &
waiter=$!
until [ -s "$work/out" ]; do sleep 0.1; done  # it has said that it waits
flock -u 9
wait "$waiter" || fail "it did not go on once the lock was released: $(cat "$work/out")"
waiter=""
grep -q "waiting for it, at most 600 s" "$work/out" || fail "no line saying it waits"
exec 9>&-
echo "setup_waits_for_apt_locks: waits for a held lock, says so, ends at its bound"
