# Sourced by scripts/setup (bash): waits while another apt or dpkg holds the package locks, as on
# a fresh cloud machine whose first automatic upgrade (unattended-upgrades, cloud-init) is still
# running; apt-get failed at once there ("Could not get lock /var/lib/dpkg/lock-frontend").

# The locks apt-get update and install take.
apt_lock_files=(/var/lib/dpkg/lock-frontend /var/lib/dpkg/lock /var/lib/apt/lists/lock
                /var/cache/apt/archives/lock)

# Whether any process holds a lock on FILE: /proc/locks lists every lock, fcntl (apt, dpkg) and
# flock alike, by device and inode ("MAJOR:MINOR:INODE", hex device numbers). No lock is taken
# to find out. False where FILE or /proc/locks cannot be read (apt-get's own timeout still waits).
lock_is_held() {
  local file=$1 dev inode
  [ -e "$file" ] && [ -r /proc/locks ] || return 1
  dev=$((16#$(stat -L -c %D "$file"))) inode=$(stat -L -c %i "$file") || return 1
  # Linux's st_dev: minor's low 8 bits, major's 12 bits, then minor's upper bits.
  local id
  id=$(printf '%02x:%02x:%s' $(((dev >> 8) & 0xfff)) $(((dev & 0xff) | ((dev >> 12) & 0xfff00))) \
       "$inode")
  grep -q " $id " /proc/locks
}

# wait_for_apt_locks TIMEOUT [FILE...]: returns once no lock on the FILEs (apt_lock_files by
# default) is held, saying once that it waits and for what; fails after TIMEOUT seconds, naming
# the lock still held.
wait_for_apt_locks() {
  local timeout=$1
  shift
  local files=("$@")
  ((${#files[@]})) || files=("${apt_lock_files[@]}")
  local waited=0 said="" file held
  while true; do
    held=""
    for file in "${files[@]}"; do
      if lock_is_held "$file"; then
        held=$file
        break
      fi
    done
    [ -z "$held" ] && return 0
    if [ -z "$said" ]; then
      echo "aief: another apt or dpkg holds $held (an automatic upgrade?): waiting for it, at most ${timeout} s"
      said=1
    fi
    if ((waited >= timeout)); then
      echo "aief: $held is still held after ${timeout} s: run scripts/setup again once that apt or dpkg has ended" >&2
      return 1
    fi
    sleep 1
    waited=$((waited + 1))
  done
}
