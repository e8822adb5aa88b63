# Sourced by the daemon integration scripts: re-runs the calling script inside a private
# network namespace with only the loopback interface up, so that no DDS traffic (discovery or
# data) can reach any network. Needs root (or user namespaces).
if [ -z "${LITAMIN2_IN_NETNS:-}" ]; then
  export LITAMIN2_IN_NETNS=1
  exec unshare -n sh -c 'ip link set lo up && exec bash "$0" "$@"' "$0" "$@"
fi
