#!/bin/sh
# The image's entrypoint: `robodds-entrypoint robodds host ARGS...`. Before it runs robodds (exec:
# robodds stays PID 1 and gets docker's SIGTERM itself), it checks that what robodds will read is
# readable by this container's user (uid 10001, robodds): bind mounts keep the host's owners and
# modes, so a key file of mode 0600 or a folder of mode 0700 on the host is unreadable in here, and
# robodds would otherwise fail deep inside Fast DDS. Checked: deploy/qos, $ROBODDS_QOS_FILE, and the
# values of --scenario, --params and --security (recursively). Exit 2 (bad input) with one line
# naming the first unreadable path.
set -eu

check_readable() {
  [ -e "$1" ] || return 0  # missing: robodds names it
  bad="$(find -L "$1" \( ! -readable -o -type d ! -executable \) -print 2>&1 | head -n 1)" || true
  if [ -n "$bad" ]; then
    echo "robodds: error: ${bad%%: Permission denied*} is not readable by uid $(id -u) ($(id -un 2>/dev/null || echo '?')), the image's user:" \
      "bind-mounted files must be readable by uid 10001 (on the host: chown -R 10001 the folder, or chmod -R a+rX if nothing in it is secret), see docs/deployment.md" >&2
    exit 2
  fi
}

check_readable /opt/robodds/deploy/qos
[ -z "${ROBODDS_QOS_FILE:-}" ] || check_readable "$ROBODDS_QOS_FILE"
[ -z "${ROBODDS_SECURITY_DIR:-}" ] || check_readable "$ROBODDS_SECURITY_DIR"
previous=""
for arg in "$@"; do
  case "$previous" in
    --scenario | --params | --security) check_readable "$arg" ;;
  esac
  previous="$arg"
done
exec "$@"
